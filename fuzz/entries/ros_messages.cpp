// The ROS1 message decoders and their conversions to the project's types (io/ros_messages.h,
// io/ros_convert.h), as the bag reader applies them; byte 0 picks the message type. A bad message is a
// WireError, which the bag reader turns into an InputError naming bag, topic and message.
#include <vector>

#include "entry_util.h"
#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam::fuzz {

Outcome ros_messages(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::vector<std::uint8_t> bytes(data + 1, data + size);
  try {
    switch (data[0] % 6) {
      case 0: {
        const RosImage image = decode_ros_image(bytes);
        check_ros_image(image);
        grey_from_ros_image(image);
        break;
      }
      case 1:
        grey_from_ros_compressed_image(decode_ros_compressed_image(bytes));
        break;
      case 2:
        decode_ros_imu(bytes);
        break;
      case 3: {
        const RosPointCloud2 cloud = decode_ros_point_cloud2(bytes);
        point_cloud2_layout(cloud);
        scan_from_point_cloud2(cloud);
        break;
      }
      case 4:
        decode_ros_pose_stamped(bytes);
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
