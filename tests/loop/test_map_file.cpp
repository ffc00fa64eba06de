// Saved maps (loop/map_file.h): an exact round trip, every kind of bad or foreign map refused with the file named,
// and `vilslam map-info` on both.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "common/error.h"
#include "io/synthetic_dataset.h"
#include "loop/map_file.h"
#include "test_util.h"

namespace vilslam::loop {
namespace {

namespace fs = std::filesystem;

KeyFrame synthetic_key_frame(std::size_t pose_index, TimeNs t_ns, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  KeyFrame k;
  k.pose_index = pose_index;
  k.scan_t_ns = t_ns;
  k.image.t_ns = t_ns - 5'000'000;
  k.image.focal_px = 458.6;
  k.T_L_C0 = SE3::exp((Vec6() << u(rng), u(rng), u(rng), 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)).finished());
  const int rows = 40;
  k.image.descriptors = cv::Mat(rows, 32, CV_8U);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 32; ++c) k.image.descriptors.at<unsigned char>(r, c) = static_cast<unsigned char>(rng());
    k.image.left_norm.emplace_back(u(rng), u(rng));
    k.image.points_C0.push_back(r % 3 == 0 ? Vec3::Constant(std::nan("")) : Vec3(u(rng), u(rng), 5.0 + u(rng)));
  }
  for (WordId w = 3; w < 300; w += 7) k.image.bow[w] = 0.01 * (1.0 + u(rng));
  k.features_L.t_ns = t_ns - 100'000'000;
  for (int i = 0; i < 25; ++i) {
    k.features_L.edges.push_back({Vec3(u(rng), u(rng), u(rng)) * 10.0, 0.05f, 0.3f});
    k.features_L.surfaces.push_back({Vec3(u(rng), u(rng), u(rng)) * 10.0, 0.07f, 0.001f});
  }
  return k;
}

SavedMap synthetic_map() {
  std::mt19937_64 rng(5);
  SavedMap map;
  map.rig = test::synthetic_calibration();
  for (int i = 0; i < 30; ++i) {
    map.poses.push_back({1'000'000'000 + i * 100'000'000LL, SE3(Quat::Identity(), Vec3(0.5 * i, 0.1 * i, 0.0))});
  }
  map.key_frames.push_back(synthetic_key_frame(4, map.poses[4].t_ns, rng));
  map.key_frames.push_back(synthetic_key_frame(17, map.poses[17].t_ns, rng));
  map.vocabulary_id = 0x0123456789abcdefull;
  return map;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void replace_in_file(const fs::path& p, const std::string& from, const std::string& to) {
  std::string text = read_text(p);
  text.replace(text.find(from), from.size(), to);
  test::write_file_bytes(p, text);
}

// load_map throws an InputError naming the file `name` of dir, with `problem` in its message.
void expect_refused(const fs::path& dir, const std::string& name, const std::string& problem) {
  try {
    load_map(dir.string());
    ADD_FAILURE() << "accepted a map with " << problem;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / name).string()) << e.what();
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  }
}

TEST(MapFile, RoundTripIsExact) {
  const fs::path dir = test::temp_dir() / "map";
  const SavedMap map = synthetic_map();
  save_map(dir.string(), map);
  EXPECT_FALSE(fs::exists(dir.string() + ".partial"));
  const SavedMap back = load_map(dir.string());
  EXPECT_EQ(back.vocabulary_id, map.vocabulary_id);
  EXPECT_EQ(back.rig.cam0.fx, map.rig.cam0.fx);
  ASSERT_EQ(back.poses.size(), map.poses.size());
  ASSERT_EQ(back.key_frames.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const KeyFrame &a = map.key_frames[i], &b = back.key_frames[i];
    EXPECT_EQ(b.id, i);
    EXPECT_EQ(b.pose_index, a.pose_index);
    EXPECT_EQ(b.scan_t_ns, a.scan_t_ns);
    EXPECT_EQ(b.image.t_ns, a.image.t_ns);
    EXPECT_EQ(b.image.focal_px, a.image.focal_px);
    EXPECT_LT((b.T_L_C0.matrix() - a.T_L_C0.matrix()).norm(), 1e-14);
    EXPECT_EQ(cv::norm(b.image.descriptors, a.image.descriptors, cv::NORM_HAMMING), 0.0);
    EXPECT_EQ(b.image.left_norm, a.image.left_norm);
    for (std::size_t r = 0; r < a.image.points_C0.size(); ++r) {
      if (a.image.points_C0[r].allFinite()) EXPECT_EQ(b.image.points_C0[r], a.image.points_C0[r]);
      else EXPECT_TRUE(b.image.points_C0[r].array().isNaN().all());
    }
    EXPECT_EQ(b.image.num_points(), a.image.num_points());
    EXPECT_EQ(b.image.bow, a.image.bow);
    EXPECT_EQ(b.features_L.t_ns, a.features_L.t_ns);
    ASSERT_EQ(b.features_L.edges.size(), a.features_L.edges.size());
    ASSERT_EQ(b.features_L.surfaces.size(), a.features_L.surfaces.size());
    EXPECT_EQ(b.features_L.surfaces[7].p_L, a.features_L.surfaces[7].p_L);
    EXPECT_EQ(b.features_L.edges[3].smoothness, a.features_L.edges[3].smoothness);
  }
  // Saved again, the same bytes.
  const fs::path again = dir.parent_path() / "again";
  save_map(again.string(), back);
  EXPECT_EQ(read_text(again / "key_frames.bin"), read_text(dir / "key_frames.bin"));
}

TEST(MapFile, BadOrIncompleteMapsNameTheFile) {
  const fs::path root = test::temp_dir();
  const fs::path good = root / "good";
  save_map(good.string(), synthetic_map());
  const std::string bin = read_text(good / "key_frames.bin");
  const auto variant = [&](const std::string& name) {
    const fs::path dir = root / name;
    fs::copy(good, dir, fs::copy_options::recursive);
    return dir;
  };
  {
    const fs::path dir = variant("no_yaml");
    fs::remove(dir / "map.yaml");
    expect_refused(dir, "map.yaml", "missing");
  }
  {
    const fs::path dir = variant("version");
    replace_in_file(dir / "map.yaml", "version: 1", "version: 2");
    expect_refused(dir, "map.yaml", "map version 2");
  }
  {
    const fs::path dir = variant("foreign_yaml");
    test::write_file_bytes(dir / "map.yaml", "format: something-else\n");
    expect_refused(dir, "map.yaml", "not a vilslam map");
  }
  for (const std::size_t cut : {std::size_t{5}, std::size_t{40}, bin.size() / 2, bin.size() - 1}) {
    const fs::path dir = variant("cut" + std::to_string(cut));
    test::write_file_bytes(dir / "key_frames.bin", bin.substr(0, cut));
    expect_refused(dir, "key_frames.bin", "truncated");
  }
  {
    const fs::path dir = variant("trailing");
    test::write_file_bytes(dir / "key_frames.bin", bin + "x");
    expect_refused(dir, "key_frames.bin", "trailing bytes");
  }
  {
    const fs::path dir = variant("magic");
    std::string b = bin;
    b[0] = 'X';
    test::write_file_bytes(dir / "key_frames.bin", b);
    expect_refused(dir, "key_frames.bin", "bad magic");
  }
  {
    // The first key frame's descriptor row count (after magic, version, count, pose index, two times, focal
    // length, seven pose values) claims 4e9 rows: refused before anything is allocated.
    const fs::path dir = variant("rows");
    std::string b = bin;
    const std::size_t at = 17 + 4 + 8 + 8 + 8 + 8 + 8 + 7 * 8;
    const std::uint32_t rows = 4'000'000'000u;
    b.replace(at, 4, reinterpret_cast<const char*>(&rows), 4);
    test::write_file_bytes(dir / "key_frames.bin", b);
    expect_refused(dir, "key_frames.bin", "do not fit");
  }
  {
    const fs::path dir = variant("nan");
    std::string b = bin;
    const double nan = std::nan("");
    b.replace(17 + 4 + 8 + 8 + 8 + 8, 8, reinterpret_cast<const char*>(&nan), 8);  // the focal length
    test::write_file_bytes(dir / "key_frames.bin", b);
    expect_refused(dir, "key_frames.bin", "non-finite");
  }
  {
    // Ten poses (after the header line), fewer than a key frame's index needs, and map.yaml says ten too.
    const fs::path dir = variant("poses");
    std::string tum = read_text(dir / "poses.tum");
    std::size_t at = 0;
    for (int line = 0; line < 11; ++line) at = tum.find('\n', at) + 1;
    test::write_file_bytes(dir / "poses.tum", tum.substr(0, at));
    replace_in_file(dir / "map.yaml", "poses: 30", "poses: 10");
    expect_refused(dir, "key_frames.bin", "beyond poses.tum");
  }
  {
    const fs::path dir = variant("count");
    replace_in_file(dir / "map.yaml", "key_frames: 2", "key_frames: 3");
    expect_refused(dir, "key_frames.bin", "map.yaml says 3");
  }
}

TEST(MapFile, ForeignVocabularyOrRigIsRefused) {
  const fs::path dir = test::temp_dir() / "map";
  const SavedMap map = synthetic_map();
  save_map(dir.string(), map);
  const SavedMap back = load_map(dir.string());
  EXPECT_NO_THROW(check_map_fits(back, dir.string(), map.vocabulary_id, map.rig));
  try {
    check_map_fits(back, dir.string(), map.vocabulary_id + 1, map.rig);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "map.yaml").string());
    EXPECT_NE(std::string(e.what()).find("another vocabulary"), std::string::npos) << e.what();
  }
  RigCalibration moved = map.rig;
  moved.T_I_C0.translation().x() += 0.002;
  EXPECT_THROW(check_map_fits(back, dir.string(), map.vocabulary_id, moved), InputError);
  RigCalibration close = map.rig;
  close.T_I_C0.translation().x() += 0.0005;  // within 1 mm: the same rig, calibrated again
  close.cam0.fx += 0.3;
  EXPECT_NO_THROW(check_map_fits(back, dir.string(), map.vocabulary_id, close));
  RigCalibration other_camera = map.rig;
  other_camera.cam1.width_px += 16;
  EXPECT_THROW(check_map_fits(back, dir.string(), map.vocabulary_id, other_camera), InputError);
}

TEST(MapFile, VocabularyIdentityIsOfTheFilesBytes) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "a.voc", "same bytes");
  test::write_file_bytes(dir / "b.voc", "same bytes");
  test::write_file_bytes(dir / "c.voc", "same bytez");
  EXPECT_EQ(vocabulary_identity((dir / "a.voc").string()), vocabulary_identity((dir / "b.voc").string()));
  EXPECT_NE(vocabulary_identity((dir / "a.voc").string()), vocabulary_identity((dir / "c.voc").string()));
  EXPECT_THROW(vocabulary_identity((dir / "missing.voc").string()), InputError);
}

TEST(MapInfoCli, ReadsAGoodMapAndRefusesABadOneWithExitTwo) {
  const fs::path root = test::temp_dir();
  const fs::path dir = root / "map";
  save_map(dir.string(), synthetic_map());
  test::CliResult r = test::run_cli("map-info " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("key frames 2 (3D points 52"), std::string::npos) << r.output;
  r = test::run_cli("map-info " + dir.string() + " --vocabulary default");
  EXPECT_EQ(r.exit_code, 2) << r.output;  // not the shipped vocabulary's identity
  EXPECT_NE(r.output.find("map.yaml"), std::string::npos) << r.output;
  const std::string bin = read_text(dir / "key_frames.bin");
  test::write_file_bytes(dir / "key_frames.bin", bin.substr(0, bin.size() / 3));
  r = test::run_cli("map-info " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("key_frames.bin"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace vilslam::loop
