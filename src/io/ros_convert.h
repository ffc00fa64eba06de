#pragma once
// ROS1 messages <-> the project's sensor types. Errors are WireErrors saying what is wrong with the
// message; the bag reader adds the file, topic and message time.
#include <string>

#include "common/types.h"
#include "io/ros_messages.h"

namespace vilslam {

// sensor_msgs/Image as an 8-bit grey image (any row padding; docs/formats.md lists the encodings): colour by
// cv::cvtColor (R = G = B = v gives v exactly), Bayer mosaics demosaiced to grey, 16-bit samples (either
// byte order) scaled so that 2^significant_bits - 1 becomes 255, rounded, larger samples clipped.
cv::Mat grey_from_ros_image(const RosImage& image, int significant_bits = 16);
// Bits a 16-bit image's samples use (8 to 16: the smallest b >= 8 with max sample < 2^b); 0 for 8-bit encodings.
int ros_image_significant_bits(const RosImage& image);
// Cheap check of the same message without converting: encoding, sizes, data length.
void check_ros_image(const RosImage& image);
// sensor_msgs/CompressedImage (PNG or JPEG; the format string is informative) decoded to 8-bit grey.
cv::Mat grey_from_ros_compressed_image(const RosCompressedImage& image);
// An 8-bit grey image as a mono8 sensor_msgs/Image.
RosImage ros_image_from_grey(const cv::Mat& grey, TimeNs t_ns, const std::string& frame_id);

// sensor_msgs/Imu as a sample (orientation and covariances unused); a non-finite rate or force is a WireError.
ImuSample imu_sample_from_ros(const RosImu& imu);
// A sample as sensor_msgs/Imu (frame imu0, orientation_covariance[0] = -1: no orientation).
RosImu ros_imu_from_sample(const ImuSample& sample);
// A ground-truth state's pose T_W_I as geometry_msgs/PoseStamped (frame world).
RosPoseStamped ros_pose_from_state(const GroundTruthState& state);

// The driver layout a PointCloud2 follows, named after its time field (docs/formats.md):
// "velodyne" (time, s since the stamp), "ouster" (t, ns since the stamp), "hesai" (timestamp, absolute,
// with ring), "livox" (timestamp without ring, or offset_time in ns since the stamp), "xyz" (no time).
std::string point_cloud2_layout(const RosPointCloud2& cloud);
// A PointCloud2 as a sweep: x y z (required), intensity, ring (has_ring when present) and per-point time.
// Points with a non-finite coordinate or at the origin (no return) are dropped. t_ns is the stamp, or the
// earliest point's time when a point lies before it; offsets count from t_ns.
LidarScan scan_from_point_cloud2(const RosPointCloud2& cloud);
// A sweep in the Velodyne driver's layout (velodyne_pointcloud PointcloudXYZIRT: x y z intensity float32,
// ring uint16, time float32 seconds since the stamp; 22 bytes a point, packed), stamp = scan.t_ns.
// Without rings (has_ring false) the ring field is left out (20 bytes a point).
RosPointCloud2 velodyne_point_cloud2(const LidarScan& scan, const std::string& frame_id);

}  // namespace vilslam
