// ROS1 message (de)serialization and the PointCloud2 layouts, without a bag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "io/ros_convert.h"
#include "io/ros_messages.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

RosPointCloud2 cloud_with_time_field(const char* name, RosPointType type, const std::vector<double>& times) {
  RosPointCloud2 m;
  m.header.stamp_ns = 1'700'000'000'500'000'000;
  const auto f32 = static_cast<std::uint8_t>(RosPointType::kFloat32);
  m.fields = {{"x", 0, f32, 1}, {"y", 4, f32, 1}, {"z", 8, f32, 1}, {name, 12, static_cast<std::uint8_t>(type), 1}};
  m.point_step = 12 + static_cast<std::uint32_t>(ros_point_type_size(static_cast<std::uint8_t>(type)));
  m.width = static_cast<std::uint32_t>(times.size());
  m.row_step = m.width * m.point_step;
  WireWriter w;
  for (std::size_t i = 0; i < times.size(); ++i) {
    w.write(1.0f + static_cast<float>(i));
    w.write(2.0f);
    w.write(3.0f);
    if (type == RosPointType::kFloat32) w.write(static_cast<float>(times[i]));
    if (type == RosPointType::kFloat64) w.write(times[i]);
    if (type == RosPointType::kUint32) w.write(static_cast<std::uint32_t>(times[i]));
  }
  m.data = w.release();
  return decode_ros_point_cloud2(encode(m));  // through the wire format
}

TEST(RosMessages, HeaderBytesAreTheRosWireFormat) {
  RosPoseStamped m;
  m.header.seq = 7;
  m.header.stamp_ns = 3'000'000'005;
  m.header.frame_id = "ab";
  const auto bytes = encode(m);
  // seq, sec, nsec (uint32 little-endian), frame_id length and characters, then 7 float64.
  const std::vector<std::uint8_t> head = {7, 0, 0, 0, 3, 0, 0, 0, 5, 0, 0, 0, 2, 0, 0, 0, 'a', 'b'};
  ASSERT_EQ(bytes.size(), head.size() + 7 * 8);
  EXPECT_TRUE(std::equal(head.begin(), head.end(), bytes.begin()));
  EXPECT_EQ(decode_ros_pose_stamped(bytes).header.stamp_ns, m.header.stamp_ns);
}

TEST(RosMessages, TruncatedOrOversizedMessagesAreErrors) {
  RosImu imu;
  auto bytes = encode(imu);
  bytes.pop_back();
  EXPECT_THROW(decode_ros_imu(bytes), WireError);
  bytes.push_back(0);
  bytes.push_back(0);
  EXPECT_THROW(decode_ros_imu(bytes), WireError);  // a byte left over: another type
}

TEST(RosMessages, VelodyneTimesBeforeTheStampMoveTheScanStart) {
  // Drivers that stamp the end of the sweep give negative times: the scan starts at the earliest point.
  const LidarScan scan = scan_from_point_cloud2(cloud_with_time_field("time", RosPointType::kFloat32, {-0.1, -0.05, 0}));
  EXPECT_NEAR(static_cast<double>(scan.t_ns - 1'700'000'000'400'000'000), 0.0, 2.0);  // float32 -0.1
  ASSERT_EQ(scan.points.size(), 3u);
  EXPECT_NEAR(scan.points[0].t_offset_s, 0.0, 1e-9);
  EXPECT_NEAR(scan.points[2].t_offset_s, 0.1, 1e-8);
  EXPECT_FALSE(scan.has_ring);
}

TEST(RosMessages, TimeFieldUnits) {
  const LidarScan ouster = scan_from_point_cloud2(cloud_with_time_field("t", RosPointType::kUint32, {0, 25'000'000}));
  EXPECT_NEAR(ouster.points[1].t_offset_s, 0.025, 1e-9);
  const double stamp_s = 1'700'000'000.5;
  const LidarScan hesai = scan_from_point_cloud2(cloud_with_time_field("timestamp", RosPointType::kFloat64, {stamp_s, stamp_s + 0.05}));
  EXPECT_NEAR(hesai.points[1].t_offset_s, 0.05, 5e-7);
  const LidarScan livox = scan_from_point_cloud2(
      cloud_with_time_field("timestamp", RosPointType::kFloat64, {stamp_s * 1e9, stamp_s * 1e9 + 5e7}));
  EXPECT_NEAR(livox.points[1].t_offset_s, 0.05, 5e-7);
  EXPECT_EQ(point_cloud2_layout(cloud_with_time_field("timestamp", RosPointType::kFloat64, {stamp_s})), "livox");
  // Neither seconds nor nanoseconds near the stamp: an error, not a silent guess.
  EXPECT_THROW(scan_from_point_cloud2(cloud_with_time_field("timestamp", RosPointType::kFloat64, {12345.0})), WireError);
}

TEST(RosMessages, PointsWithoutReturnAreDropped) {
  RosPointCloud2 m = cloud_with_time_field("time", RosPointType::kFloat32, {0, 0.01});
  std::memset(m.data.data(), 0, 12);  // first point at the origin
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(m.data.data() + m.point_step, &nan, 4);
  EXPECT_TRUE(scan_from_point_cloud2(m).points.empty());
}

TEST(RosMessages, BigEndianCloudsReadAsLittleEndianOnes) {
  LidarScan scan;
  scan.t_ns = 1'700'000'000'000'000'000;
  scan.has_ring = true;
  for (int i = 0; i < 5; ++i) {
    LidarPoint p;
    p.x = 1.5f + i;
    p.y = -2.25f * i;
    p.z = 0.125f;
    p.intensity = 10.0f * i;
    p.ring = static_cast<std::uint16_t>(3 * i);
    p.t_offset_s = 0.01f * i;
    scan.points.push_back(p);
  }
  const RosPointCloud2 little = velodyne_point_cloud2(scan, "lidar0");
  RosPointCloud2 big = little;
  big.is_bigendian = 1;
  for (std::uint32_t k = 0; k < big.width; ++k) {  // each field's bytes reversed
    for (const RosPointField& f : big.fields) {
      auto* at = big.data.data() + std::size_t{k} * big.point_step + f.offset;
      std::reverse(at, at + ros_point_type_size(f.datatype));
    }
  }
  ASSERT_NE(big.data, little.data);
  const LidarScan a = scan_from_point_cloud2(little), b = scan_from_point_cloud2(big);
  ASSERT_EQ(a.points.size(), 5u);
  ASSERT_EQ(b.points.size(), 5u);
  EXPECT_EQ(b.t_ns, a.t_ns);
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(b.points[i].x, scan.points[i].x);
    EXPECT_EQ(b.points[i].y, scan.points[i].y);
    EXPECT_EQ(b.points[i].intensity, scan.points[i].intensity);
    EXPECT_EQ(b.points[i].ring, scan.points[i].ring);
    EXPECT_EQ(b.points[i].t_offset_s, a.points[i].t_offset_s);
  }
}

}  // namespace
}  // namespace vilslam
