// Connection records of the written types: datatype, MD5 and definition as ROS's message generators
// produce them (values of the Debian 12 python3-sensor-msgs 1.13.1 / python3-geometry-msgs classes,
// comments dropped from the definitions; the MD5 is computed from the comment-free text anyway).
#include "io/ros_messages.h"

#define VILSLAM_ROS_SEP "================================================================================\n"
#define VILSLAM_ROS_HEADER_DEF \
  "MSG: std_msgs/Header\n"     \
  "uint32 seq\n"               \
  "time stamp\n"               \
  "string frame_id\n"

#define VILSLAM_ROS_QUATERNION_DEF \
  "MSG: geometry_msgs/Quaternion\n" \
  "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"

namespace vilslam {

const RosMessageType kRosImage{"sensor_msgs/Image", "060021388200f6f0f447d0fcd9c64743",
                               "Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\n"
                               "uint32 step\nuint8[] data\n"
                               VILSLAM_ROS_SEP
                               VILSLAM_ROS_HEADER_DEF};

const RosMessageType kRosCompressedImage{
    "sensor_msgs/CompressedImage", "8f7a12909da2c9d3332d540a0977563f",
    "Header header\nstring format\nuint8[] data\n"
    VILSLAM_ROS_SEP VILSLAM_ROS_HEADER_DEF};

const RosMessageType kRosImu{
    "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2",
    "Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
    "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
    "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n"
    VILSLAM_ROS_SEP VILSLAM_ROS_HEADER_DEF
    VILSLAM_ROS_SEP VILSLAM_ROS_QUATERNION_DEF
    VILSLAM_ROS_SEP
    "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n"};

const RosMessageType kRosPointCloud2{
    "sensor_msgs/PointCloud2", "1158d486dd51d683ce2f1be655c3c181",
    "Header header\nuint32 height\nuint32 width\nPointField[] fields\nbool    is_bigendian\nuint32  point_step\n"
    "uint32  row_step\nuint8[] data\nbool is_dense\n"
    VILSLAM_ROS_SEP VILSLAM_ROS_HEADER_DEF
    VILSLAM_ROS_SEP
    "MSG: sensor_msgs/PointField\nuint8 INT8    = 1\nuint8 UINT8   = 2\nuint8 INT16   = 3\nuint8 UINT16  = 4\n"
    "uint8 INT32   = 5\nuint8 UINT32  = 6\nuint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\nstring name\nuint32 offset\n"
    "uint8  datatype\nuint32 count\n"};

const RosMessageType kRosPoseStamped{
    "geometry_msgs/PoseStamped", "d3812c3cbc69362b77dc0b19b345f8f5",
    "Header header\nPose pose\n"
    VILSLAM_ROS_SEP VILSLAM_ROS_HEADER_DEF
    VILSLAM_ROS_SEP
    "MSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n"
    VILSLAM_ROS_SEP
    "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n"
    VILSLAM_ROS_SEP VILSLAM_ROS_QUATERNION_DEF};

}  // namespace vilslam
