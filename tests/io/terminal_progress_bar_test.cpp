// Tests of io/terminal_progress_bar.h's pure line renderer: bar, percentage, items and time,
// and the parts dropped on narrow terminals (the bar on a real pseudo-terminal:
// tests/tools/progress_terminal_test.cpp).
#include "io/terminal_progress_bar.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace imunoise::io {
namespace {

TEST(ProgressLineRender, HalfWayLineHasBarPercentItemsAndTime) {
  ProgressLine p;
  p.label = "analyze";
  p.stage = "deviations";
  p.done = 3;
  p.total = 6;
  p.items_done = 3;
  p.items_total = 6;
  p.items_unit = "channels";
  p.elapsed_s = 4.7;
  const std::string line = render_progress_line(p, 80);
  EXPECT_LE(line.size(), 79u);
  EXPECT_EQ(line.rfind("analyze: deviations [", 0), 0u) << line;
  const auto open = line.find('[');
  const auto close = line.find(']');
  ASSERT_NE(close, std::string::npos);
  const std::string bar = line.substr(open + 1, close - open - 1);
  const auto filled = static_cast<std::size_t>(std::count(bar.begin(), bar.end(), '#'));
  EXPECT_EQ(filled, bar.size() / 2) << line;
  EXPECT_EQ(bar.find_first_not_of('#'), filled) << "the filled part comes first: " << line;
  EXPECT_NE(line.find("]  50%  3/6 channels  0:04"), std::string::npos) << line;
}

TEST(ProgressLineRender, FullLineAndLongTimes) {
  ProgressLine p;
  p.label = "simulate";
  p.stage = "done";
  p.stage_width = 10;
  p.done = 7;
  p.total = 7;
  p.elapsed_s = 3725.0;
  const std::string line = render_progress_line(p, 100);
  EXPECT_LE(line.size(), 99u);
  EXPECT_EQ(line.rfind("simulate: done       [", 0), 0u) << line;  // stage padded to 10
  EXPECT_NE(line.find("] 100%  1:02:05"), std::string::npos) << line;
  EXPECT_EQ(line.find(' ', line.find('[')), line.find(']') + 1) << "bar full: " << line;
  // 99.9 % is not 100 %: the full state is reserved for the end.
  p.done = 999;
  p.total = 1000;
  EXPECT_NE(render_progress_line(p, 100).find(" 99%"), std::string::npos);
  p.done = 5;  // out-of-range input is clamped, not trusted
  p.total = 0;
  EXPECT_NE(render_progress_line(p, 100).find("  0%"), std::string::npos);
}

TEST(ProgressLineRender, NarrowTerminalsDropPartsButNeverOverflow) {
  ProgressLine p;
  p.label = "analyze";
  p.stage = "bootstrap";
  p.done = 1;
  p.total = 4;
  p.items_done = 2;
  p.items_total = 6;
  p.items_unit = "channels";
  for (int columns : {200, 80, 50, 40, 30, 20, 10, 2, 1, 0}) {
    const std::string line = render_progress_line(p, columns);
    EXPECT_LE(static_cast<int>(line.size()), std::max(columns - 1, 0)) << columns << ": " << line;
  }
  EXPECT_EQ(render_progress_line(p, 50).find("channels"), std::string::npos)
      << "the item count goes before the bar does";
  EXPECT_NE(render_progress_line(p, 50).find('['), std::string::npos);
  EXPECT_EQ(render_progress_line(p, 30), "analyze: bootstrap  25%  0:00");
}

}  // namespace
}  // namespace imunoise::io
