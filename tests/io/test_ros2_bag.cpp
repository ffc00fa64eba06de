// ROS 2 bags (rosbag2 sqlite3 storage, CDR) written from the synthetic dataset with eProsima Fast CDR read
// back event for event as that folder, in either byte order and split over files; what the reader cannot
// read is refused naming the file.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset.h"
#include "io/message_log.h"
#include "ros2_bag_writer.h"
#include "rosbag_test_util.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class Ros2BagRead : public test::RosbagFixture {
 protected:
  // The synthetic folder as a ROS 2 bag folder dir_/name, with its calibration beside it (name.rig.yaml).
  fs::path ros2_bag(const std::string& name, const test::Ros2BagOptions& options = {}) {
    const fs::path bag = dir_ / name;
    test::write_ros2_bag(*open_dataset(folder_), bag, options);
    fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / (name + ".rig.yaml"));
    return bag;
  }

  void expect_refused(const std::string& path, const std::vector<std::string>& says) {
    try {
      open_dataset(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const InputError& e) {
      for (const std::string& s : says) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
    }
  }

  test::StreamTolerance tolerance() const {
    test::StreamTolerance tol;
    tol.groundtruth_pose_only = true;  // PoseStamped carries no velocity or biases
    return tol;
  }
};

TEST_F(Ros2BagRead, ReadsAsTheFolderInEitherByteOrderAndSplitOverFiles) {
  for (const bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "CDR big-endian, 3 files" : "CDR little-endian, 3 files");
    const fs::path bag = ros2_bag(big_endian ? "be" : "le", {big_endian, 3});
    const auto from_bag = open_dataset(bag.string());
    EXPECT_EQ(from_bag->summary().format, "rosbag2");
    const auto from_folder = open_dataset(folder_);
    EXPECT_EQ(test::expect_same_events(*from_folder, *from_bag, tolerance()), 100u + 10u + 5u + 50u);
  }
}

TEST_F(Ros2BagRead, OneDb3FileAndTheCli) {
  const fs::path bag = ros2_bag("single");
  const fs::path db3 = bag / "single_0.db3";
  fs::copy_file(fs::path(folder_) / "rig.yaml", bag / "single_0.rig.yaml");
  const auto from_file = open_dataset(db3.string());
  EXPECT_EQ(test::expect_same_events(*open_dataset(folder_), *from_file, tolerance()), 100u + 10u + 5u + 50u);
  const fs::path json = dir_ / "info.json";
  const auto r = test::run_cli("info " + bag.string() + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const YAML::Node info = YAML::LoadFile(json.string());
  EXPECT_EQ(info["format"].as<std::string>(), "rosbag2");
  std::vector<std::string> topics;
  for (const auto& t : info["topics"]) topics.push_back(t.as<std::string>());
  EXPECT_EQ(topics, (std::vector<std::string>{"imu0 /imu0 sensor_msgs/Imu",
                                              "groundtruth /ground_truth geometry_msgs/PoseStamped",
                                              "cam0 /cam0/image_raw sensor_msgs/Image mono8",
                                              "cam1 /cam1/image_raw sensor_msgs/Image mono8",
                                              "lidar0 /points_raw sensor_msgs/PointCloud2 velodyne"}));
}

TEST_F(Ros2BagRead, RefusesWhatItCannotRead) {
  const fs::path bag = ros2_bag("good");
  const auto metadata_saying = [&](const std::string& name, const std::string& replace, const std::string& with) {
    const fs::path copy = dir_ / name;
    fs::copy(bag, copy);
    fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / (name + ".rig.yaml"));
    std::ifstream in(copy / "metadata.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text.replace(text.find(replace), replace.size(), with);
    std::ofstream(copy / "metadata.yaml") << text;
    return copy.string();
  };
  expect_refused(metadata_saying("mcap", "storage_identifier: sqlite3", "storage_identifier: mcap"),
                 {"metadata.yaml", "storage 'mcap' is not supported"});
  expect_refused(metadata_saying("zstd", "compression_format: \"\"", "compression_format: zstd"),
                 {"metadata.yaml", "compressed bag (zstd)"});
  expect_refused(metadata_saying("gone", "good_0.db3", "missing_0.db3"), {"missing_0.db3", "does not exist"});

  // Not an SQLite file.
  const fs::path garbage = dir_ / "garbage.db3";
  std::ofstream(garbage) << std::string(4096, 'x');
  fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / "garbage.rig.yaml");
  expect_refused(garbage.string(), {"garbage.db3"});

  // A message cut short: the error names the bag, the topic and the message.
  const fs::path cut = dir_ / "cut.db3";
  fs::copy_file(bag / "good_0.db3", cut);
  fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / "cut.rig.yaml");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(cut.string().c_str(), &db), SQLITE_OK);
  test::sql(db, "UPDATE messages SET data = substr(data, 1, 30) WHERE id = (SELECT MIN(id) FROM messages WHERE "
                "topic_id = (SELECT id FROM topics WHERE name = '/imu0'))");
  sqlite3_close(db);
  expect_refused(cut.string(), {"cut.db3", "topic /imu0, message 0", "truncated"});
}

TEST(Ros2BagDetect, FoldersWithMetadataAndDb3Files) {
  const fs::path dir = test::temp_dir();
  EXPECT_FALSE(is_ros2_bag(dir.string()));
  std::ofstream(dir / "metadata.yaml") << "x: 1\n";
  EXPECT_TRUE(is_ros2_bag(dir.string()));
  std::ofstream(dir / "a.db3") << "";
  EXPECT_TRUE(is_ros2_bag((dir / "a.db3").string()));
  EXPECT_FALSE(is_ros2_bag((dir / "metadata.yaml").string()));
}

}  // namespace
}  // namespace vilslam
