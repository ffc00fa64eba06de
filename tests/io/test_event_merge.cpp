#include <gtest/gtest.h>

#include "io/event_merge.h"

namespace vilslam {
namespace {

TEST(EventMerge, TimeOrderWithTiesToTheEarlierStream) {
  EventMerge merge;
  merge.add_stream({10, 20, 30});
  merge.add_stream({});
  merge.add_stream({5, 20, 40});
  merge.add_stream({20});
  using Item = std::pair<std::size_t, std::size_t>;
  const std::vector<Item> expected = {{2, 0}, {0, 0}, {0, 1}, {2, 1}, {3, 0}, {0, 2}, {2, 2}};
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Item> got;
    while (const auto item = merge.next()) got.push_back(*item);
    EXPECT_EQ(got, expected);
    merge.rewind();
  }
}

}  // namespace
}  // namespace vilslam
