// Tests of io/duration_parser.h: each unit, the range, and the messages that name what was
// read and suggest the spelling that works.
#include "io/duration_parser.h"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

TEST(ParseDuration, UnitsAreSecondsMinutesAndHours) {
  EXPECT_EQ(parse_duration_s("600", "--d"), 600.0);
  EXPECT_EQ(parse_duration_s("600s", "--d"), 600.0);
  EXPECT_EQ(parse_duration_s("0.5s", "--d"), 0.5);
  EXPECT_EQ(parse_duration_s("30min", "--d"), 1800.0);
  EXPECT_EQ(parse_duration_s("2h", "--d"), 7200.0);
  EXPECT_EQ(parse_duration_s("1.5e1min", "--d"), 900.0);
}

TEST(ParseDuration, ZeroOnlyWhenAllowed) {
  EXPECT_EQ(parse_duration_s("0", "--warmup", true), 0.0);
  EXPECT_EQ(test::error_of([] { parse_duration_s("0", "--window"); }),
            "--window: expected a positive number with unit s, min or h (e.g. 2h, 30min, "
            "600s), got '0'");
  EXPECT_EQ(test::error_of([] { parse_duration_s("-1s", "--warmup", true); }),
            "--warmup: expected a non-negative number with unit s, min or h (e.g. 2h, 30min, "
            "600s), got '-1s'");
}

TEST(ParseDuration, UsualSlipsGetTheSpellingThatWorks) {
  const auto message = [](const std::string& text) {
    return test::error_of([&] { parse_duration_s(text, "window"); });
  };
  const std::string prefix =
      "window: expected a positive number with unit s, min or h (e.g. 2h, 30min, 600s), got '";
  EXPECT_EQ(message("30 min"), prefix + "30 min' (write the unit without a space, e.g. 30min)");
  EXPECT_EQ(message("5m"), prefix + "5m' (use 'min' for minutes)");
  EXPECT_EQ(message("10secs"), prefix + "10secs' (use 's' for seconds)");
  EXPECT_EQ(message("2hours"), prefix + "2hours' (use 'h' for hours)");
  EXPECT_EQ(message("500ms"), prefix + "500ms' (the smallest unit is s: write e.g. 0.5s)");
  EXPECT_EQ(message("abc"), prefix + "abc'");
  EXPECT_EQ(message("inf"), prefix + "inf'");
  EXPECT_EQ(message(""), prefix + "'");
}

}  // namespace
}  // namespace imunoise::io
