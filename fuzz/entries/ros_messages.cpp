// The ROS1 and ROS 2 (CDR) message decoders and their conversions to the project's types (io/ros_messages.h,
// io/ros2_messages.h, io/ros_convert.h), as the bag readers apply them; byte 0 picks the message type and
// serialization (0-5 ROS1, 6-10 CDR). A bad message is a
// WireError, which the bag reader turns into an InputError naming bag, topic and message.
#include <vector>

#include "entry_util.h"
#include "io/ros2_messages.h"
#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam::fuzz {

Outcome ros_messages(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::vector<std::uint8_t> bytes(data + 1, data + size);
  try {
    const int kind = data[0] % 11;
    const bool cdr = kind >= 6;
    switch (cdr ? kind - 6 : kind) {
      case 0: {
        const RosImage image = cdr ? decode_cdr_image(bytes) : decode_ros_image(bytes);
        check_ros_image(image);
        grey_from_ros_image(image, ros_image_significant_bits(image) > 0 ? ros_image_significant_bits(image) : 16);
        break;
      }
      case 1:
        grey_from_ros_compressed_image(cdr ? decode_cdr_compressed_image(bytes) : decode_ros_compressed_image(bytes));
        break;
      case 2:
        imu_sample_from_ros(cdr ? decode_cdr_imu(bytes) : decode_ros_imu(bytes));
        break;
      case 3: {
        const RosPointCloud2 cloud = cdr ? decode_cdr_point_cloud2(bytes) : decode_ros_point_cloud2(bytes);
        point_cloud2_layout(cloud);
        scan_from_point_cloud2(cloud);
        break;
      }
      case 4:
        cdr ? decode_cdr_pose_stamped(bytes) : decode_ros_pose_stamped(bytes);
        break;
      default:
        decode_ros_header(bytes);
    }
    return {true, {}};
  } catch (const WireError& e) {
    return {false, e.what()};
  }
}

}  // namespace vilslam::fuzz
