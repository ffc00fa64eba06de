// The LZF decompressor on hand-made streams: each chunk kind, overlapping references, and corrupt input.
#include <gtest/gtest.h>

#include <string>

#include "io/lzf.h"

namespace vilslam {
namespace {

std::string bytes(std::initializer_list<int> v) {
  std::string s;
  for (int b : v) s.push_back(static_cast<char>(b));
  return s;
}

std::string decompress(const std::string& in, std::size_t expected) {
  return lzf_decompress(in.data(), in.size(), expected);
}

TEST(Lzf, LiteralRunsAndBackReferences) {
  // "abc" literal (ctrl 2), then a reference of 3 + 2 = 5... encoded as ctrl (3 << 5) | 0, distance byte 2
  // (D = 3): copies "abcab" from 3 back, overlapping the bytes it writes.
  EXPECT_EQ(decompress(bytes({2, 'a', 'b', 'c', (3 << 5) | 0, 2}), 8), "abcabcab");
  // A long reference: L = 7 + 10 = 17, +2 = 19 copies of the one byte before (D = 1): run-length.
  EXPECT_EQ(decompress(bytes({0, 'x', (7 << 5) | 0, 10, 0}), 20), std::string(20, 'x'));
  // The distance's high bits live in the control byte: D = (1 << 8) + 0 + 1 = 257.
  std::string lit(257, '\0');
  std::string in;
  for (int i = 0; i < 257; ++i) lit[i] = static_cast<char>(i * 7);
  for (std::size_t at = 0; at < lit.size(); at += 32) {
    const std::size_t n = std::min<std::size_t>(32, lit.size() - at);
    in.push_back(static_cast<char>(n - 1));
    in += lit.substr(at, n);
  }
  in += bytes({(1 << 5) | 1, 0});  // L = 1 + 2 = 3 bytes from 257 back: lit[0..2]
  EXPECT_EQ(decompress(in, 260), lit + lit.substr(0, 3));
  EXPECT_EQ(decompress("", 0), "");
}

void expect_error(const std::string& in, std::size_t expected, const std::string& what) {
  try {
    decompress(in, expected);
    FAIL() << "no error for " << what;
  } catch (const LzfError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(Lzf, CorruptStreamsAreErrorsNotCrashes) {
  expect_error(bytes({5, 'a', 'b'}), 6, "literal run of 6 bytes is truncated");
  expect_error(bytes({0, 'a', (2 << 5)}), 5, "back reference is truncated");
  expect_error(bytes({0, 'a', (7 << 5)}), 12, "back reference is truncated");
  expect_error(bytes({0, 'a', (1 << 5) | 0, 1}), 4, "before the start of the output");
  expect_error(bytes({2, 'a', 'b', 'c'}), 2, "exceed the expected 2 bytes");
  expect_error(bytes({0, 'a', (7 << 5) | 0, 255, 0}), 100, "exceed the expected 100 bytes");
  expect_error(bytes({2, 'a', 'b', 'c'}), 4, "ends after 3 of the expected 4 bytes");
  expect_error(bytes({2, 'a', 'b', 'c'}), 1000, "cannot expand");
}

// Every prefix of a valid stream either decodes to the whole output or fails cleanly.
TEST(Lzf, EveryTruncationFailsCleanly) {
  const std::string in = bytes({2, 'a', 'b', 'c', (3 << 5) | 0, 2, (7 << 5) | 0, 3, 0, 1, 'z', 'y'});
  const std::size_t expected = 3 + 5 + 12 + 2;
  ASSERT_EQ(decompress(in, expected).size(), expected);
  for (std::size_t n = 0; n < in.size(); ++n) EXPECT_THROW(decompress(in.substr(0, n), expected), LzfError) << n;
}

}  // namespace
}  // namespace vilslam
