// ROS 2 bags (rosbag2's sqlite3 and MCAP storage, CDR) written from the synthetic dataset with eProsima Fast
// CDR read back event for event as that folder: sqlite3 in either byte order and split over files, MCAP with
// top-level messages or chunks (uncompressed, zstd, LZ4) stored out of order; what the readers cannot read is
// refused naming the file.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset.h"
#include "io/message_log.h"
#include "mcap_writer.h"
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
    const fs::path bag = ros2_bag(big_endian ? "be" : "le", {big_endian, 3, ""});
    const auto from_bag = open_dataset(bag.string());
    EXPECT_EQ(from_bag->summary().format, "rosbag2");
    const auto from_folder = open_dataset(folder_);
    EXPECT_EQ(test::expect_same_events(*from_folder, *from_bag, tolerance()), 100u + 10u + 5u + 50u);
  }
}

TEST_F(Ros2BagRead, ZstdCompressedByFileOrByMessage) {
  for (const char* mode : {"file", "message"}) {
    SCOPED_TRACE(mode);
    const fs::path bag = ros2_bag(std::string("zstd_") + mode, {false, 2, mode});
    const auto from_bag = open_dataset(bag.string());
    EXPECT_EQ(test::expect_same_events(*open_dataset(folder_), *from_bag, tolerance()), 100u + 10u + 5u + 50u);
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
  expect_refused(metadata_saying("rosbag_v2", "storage_identifier: sqlite3", "storage_identifier: rosbag_v2"),
                 {"metadata.yaml", "storage 'rosbag_v2' is not supported"});
  expect_refused(metadata_saying("lz4", "compression_format: \"\"", "compression_format: lz4"),
                 {"metadata.yaml", "compression 'lz4' by '' is not supported"});
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

TEST_F(Ros2BagRead, McapReadsAsTheFolderWithOrWithoutCompressedChunks) {
  struct Case {
    const char* name;
    test::McapOptions options;
  };
  const Case cases[] = {{"top_level", {0, "", false}},
                        {"chunks", {7, "", true}},
                        {"zstd", {7, "zstd", true}},
                        {"lz4", {40, "lz4", false}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path file = dir_ / (std::string(c.name) + ".mcap");
    test::write_mcap(*open_dataset(folder_), file, c.options);
    fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / (std::string(c.name) + ".rig.yaml"));
    const auto from_bag = open_dataset(file.string());
    EXPECT_EQ(from_bag->summary().format, "rosbag2");
    EXPECT_EQ(test::expect_same_events(*open_dataset(folder_), *from_bag, tolerance()), 100u + 10u + 5u + 50u);
  }
  // The same file as a bag folder whose metadata says mcap.
  const fs::path folder = dir_ / "mcap_bag";
  fs::create_directories(folder);
  fs::copy_file(dir_ / "zstd.mcap", folder / "mcap_bag_0.mcap");
  std::ofstream(folder / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: mcap\n"
                                             "  relative_file_paths: [mcap_bag_0.mcap]\n";
  fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / "mcap_bag.rig.yaml");
  EXPECT_EQ(test::expect_same_events(*open_dataset(folder_), *open_dataset(folder.string()), tolerance()),
            100u + 10u + 5u + 50u);
}

TEST_F(Ros2BagRead, McapRefusesMalformedFiles) {
  const fs::path good = dir_ / "good.mcap";
  test::write_mcap(*open_dataset(folder_), good, {7, "zstd", false});
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const auto variant = [&](const std::string& name, const std::string& content) {
    const fs::path file = dir_ / (name + ".mcap");
    std::ofstream(file, std::ios::binary) << content;
    fs::copy_file(fs::path(folder_) / "rig.yaml", dir_ / (name + ".rig.yaml"));
    return file.string();
  };
  expect_refused(variant("magic", "GIF89a" + bytes.substr(6)), {"magic.mcap", "not an MCAP file"});
  expect_refused(variant("cut", bytes.substr(0, bytes.size() / 2)), {"cut.mcap", "truncated"});
  // The first chunk's compression string renamed in place to one no reader knows.
  std::string renamed = bytes;
  const std::size_t at = renamed.find(std::string("\x04\0\0\0zstd", 8));
  ASSERT_NE(at, std::string::npos);
  renamed.replace(at + 4, 4, "zstx");
  expect_refused(variant("zstx", renamed), {"zstx.mcap", "compression 'zstx' is not supported"});
}

TEST(Ros2BagDetect, FoldersWithMetadataDb3AndMcapFiles) {
  const fs::path dir = test::temp_dir();
  EXPECT_FALSE(is_ros2_bag(dir.string()));
  std::ofstream(dir / "metadata.yaml") << "x: 1\n";
  EXPECT_TRUE(is_ros2_bag(dir.string()));
  std::ofstream(dir / "a.db3") << "";
  EXPECT_TRUE(is_ros2_bag((dir / "a.db3").string()));
  std::ofstream(dir / "a.mcap") << "";
  EXPECT_TRUE(is_ros2_bag((dir / "a.mcap").string()));
  EXPECT_FALSE(is_ros2_bag((dir / "metadata.yaml").string()));
}

}  // namespace
}  // namespace vilslam
