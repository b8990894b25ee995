// SVG text output of the plot writer (report/svg_text.h): pixel numbers, attributes, path
// data, ids and the text-width estimate, each against its documented form.

#include "report/svg_text.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "report/svg_style.h"

namespace imunoise::report::svg_detail {
namespace {

std::string number(double v) {
  std::string out;
  append_number(out, v);
  return out;
}

TEST(SvgNumber, AtMostTwoDecimalsWithoutTrailingZeros) {
  EXPECT_EQ(number(12.5), "12.5");
  EXPECT_EQ(number(3.0), "3");
  EXPECT_EQ(number(100.0), "100");  // zeros before the point stay
  EXPECT_EQ(number(1.23456), "1.23");
  EXPECT_EQ(number(-7.899), "-7.9");
}

TEST(SvgNumber, NeverMinusZeroNanOrInf) {
  EXPECT_EQ(number(-0.0), "0");
  EXPECT_EQ(number(-0.004), "0");
  EXPECT_EQ(number(std::numeric_limits<double>::quiet_NaN()), "0");
  EXPECT_EQ(number(std::numeric_limits<double>::infinity()), "0");
  EXPECT_EQ(number(1e12), "1000000000");  // clamped to ±1e9
  EXPECT_EQ(number(-1e12), "-1000000000");
}

TEST(SvgAttr, NumbersTextAndRawValues) {
  std::string out;
  attr(out, "x", 1.5);
  attr(out, "title", "a<b & \"c\"");
  attr_raw(out, "d", "M0 0 h5");
  EXPECT_EQ(out, " x=\"1.5\" title=\"a&lt;b &amp; &quot;c&quot;\" d=\"M0 0 h5\"");
}

TEST(SvgPathData, PointsAndLengths) {
  std::string d;
  path_point(d, 'M', 1.0, 2.0);
  path_point(d, 0, 3.0, 4.25);
  path_length(d, 'h', -5.0);
  path_point(d, 'L', 0.5, 0.0);
  EXPECT_EQ(d, "M1 2 3 4.25 h-5 L0.5 0");
}

TEST(SvgId, OnlyIdCharactersStartingWithALetterOrUnderscore) {
  EXPECT_EQ(sanitized_id("adev gyro/x"), "adev_gyro_x");
  EXPECT_EQ(sanitized_id("_ok-1"), "_ok-1");
  EXPECT_EQ(sanitized_id("9lives"), "p9lives");
  EXPECT_EQ(sanitized_id("-x"), "p-x");
  EXPECT_EQ(sanitized_id(""), "p");
}

TEST(SvgTextWidth, CountsCodePointsNotBytes) {
  EXPECT_DOUBLE_EQ(text_width("σ(τ)", 12.0), text_width("abcd", 12.0));
  EXPECT_DOUBLE_EQ(text_width("abc", 10.0), 3.0 * kCharWidth * 10.0);
  EXPECT_EQ(text_width("", 12.0), 0.0);
}

}  // namespace
}  // namespace imunoise::report::svg_detail
