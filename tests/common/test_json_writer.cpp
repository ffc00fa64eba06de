#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/json_writer.h"
#include "test_util.h"

namespace vilslam {
namespace {

TEST(JsonWriter, NestedContainersCommasAndEscapes) {
  JsonWriter j;
  j.begin_object();
  j.key("name").value("a \"quoted\"\\ line\n");
  j.key("n").value(3);
  j.key("x").value(0.5);
  j.key("nan").value(std::nan(""));
  j.key("ok").value(true);
  j.key("list").begin_array().value(1).value("two").begin_object().end_object().end_array();
  j.key("empty").begin_array().end_array();
  j.end_object();
  EXPECT_EQ(j.str(),
            "{\n  \"name\": \"a \\\"quoted\\\"\\\\ line\\n\",\n  \"n\": 3,\n  \"x\": 0.5,\n  \"nan\": null,\n"
            "  \"ok\": true,\n  \"list\": [\n    1,\n    \"two\",\n    {}\n  ],\n  \"empty\": []\n}\n");
}

TEST(JsonWriter, DoublesRoundTripAndSaveIsAtomic) {
  JsonWriter j;
  j.begin_array().value(0.1).value(1e-300).end_array();
  EXPECT_NE(j.str().find("0.10000000000000001"), std::string::npos);
  const auto dir = ::vilslam::test::temp_dir();
  std::filesystem::create_directories(dir);
  const auto path = dir / "out.json";
  j.save(path.string());
  std::ifstream f(path);
  std::stringstream text;
  text << f.rdbuf();
  EXPECT_EQ(text.str(), j.str());
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  EXPECT_THROW(j.save((dir / "no_such_dir" / "x.json").string()), std::runtime_error);
}

}  // namespace
}  // namespace vilslam
