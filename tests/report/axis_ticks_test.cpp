// Axis ticks of the report's plots (report/axis_ticks.h): 1-2-5 linear steps enclosing the
// range, log10 decades with minors, the degenerate inputs.
#include "report/axis_ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace imunoise::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> tick_values(const std::vector<Tick>& ticks, bool major) {
  std::vector<double> out;
  for (const auto& t : ticks) {
    if (t.major == major) out.push_back(t.value);
  }
  return out;
}

std::vector<std::string> tick_texts(const std::vector<Tick>& ticks) {
  std::vector<std::string> out;
  for (const auto& t : ticks) out.push_back(t.text);
  return out;
}

// ----------------------------------------------------------------------------------- ticks

TEST(LinearTicks, UnitRangeInTenths) {
  const auto ticks = linear_ticks(0.0, 1.0);
  EXPECT_EQ(tick_values(ticks, true), (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_EQ(tick_texts(ticks), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1"}));
}

TEST(LinearTicks, OneTwoFiveStepsEnclosingTheRange) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {-3.7, 12.2}, {0.013, 0.077}, {-250.0, -10.0}, {1.0, 1.0001}, {3e5, 4.4e7}}) {
    SCOPED_TRACE(std::to_string(lo) + " .. " + std::to_string(hi));
    const auto ticks = linear_ticks(lo, hi);
    ASSERT_GE(ticks.size(), 4u);
    EXPECT_LE(ticks.size(), 10u);
    EXPECT_LE(ticks.front().value, lo);
    EXPECT_GE(ticks.back().value, hi);
    const double step = ticks[1].value - ticks[0].value;
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
    EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-6 || std::abs(mantissa - 2.0) < 1e-6 ||
                std::abs(mantissa - 5.0) < 1e-6)
        << "step " << step;
    EXPECT_LT(ticks.front().value, lo + step * 1.0000001);  // at most one step outside
    EXPECT_GT(ticks.back().value, hi - step * 1.0000001);
    for (std::size_t i = 1; i < ticks.size(); ++i) {
      EXPECT_NEAR(ticks[i].value - ticks[i - 1].value, step, 1e-9 * step);
      EXPECT_NE(ticks[i].text, ticks[i - 1].text);
    }
  }
  const auto ticks = linear_ticks(-3.7, 12.2);
  EXPECT_EQ(tick_texts(ticks), (std::vector<std::string>{"-5", "0", "5", "10", "15"}));
}

TEST(LinearTicks, TinyValuesUseTheScientificForm) {
  const auto ticks = linear_ticks(1e-9, 3e-9);
  EXPECT_EQ(tick_texts(ticks),
            (std::vector<std::string>{"1e-09", "1.5e-09", "2e-09", "2.5e-09", "3e-09"}));
  EXPECT_EQ(tick_texts(linear_ticks(0.0, 2e6, 5)),
            (std::vector<std::string>{"0", "5e+05", "1e+06", "1.5e+06", "2e+06"}));
  EXPECT_EQ(tick_texts(linear_ticks(0.0, 0.05, 6)),
            (std::vector<std::string>{"0", "0.01", "0.02", "0.03", "0.04", "0.05"}));
}

TEST(LinearTicks, EmptyAndReversedRanges) {
  EXPECT_EQ(tick_texts(linear_ticks(0.0, 0.0)),
            (std::vector<std::string>{"-1", "-0.5", "0", "0.5", "1"}));
  const auto around_five = linear_ticks(5.0, 5.0);  // ±10 %
  EXPECT_LE(around_five.front().value, 4.5);
  EXPECT_GE(around_five.back().value, 5.5);
  EXPECT_EQ(tick_texts(linear_ticks(1.0, 0.0)), tick_texts(linear_ticks(0.0, 1.0)));
  EXPECT_TRUE(linear_ticks(0.0, kNaN).empty());
  EXPECT_TRUE(linear_ticks(-kInf, 1.0).empty());
  const auto huge = linear_ticks(-1e308, 1.7e308);
  EXPECT_FALSE(huge.empty());
  for (const auto& t : huge) EXPECT_TRUE(std::isfinite(t.value));
}

TEST(Log10Ticks, DecadesWithMinors) {
  const auto ticks = log10_ticks(3e-4, 20.0);
  EXPECT_EQ(tick_values(ticks, true),
            (std::vector<double>{1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0}));
  EXPECT_EQ(tick_texts(ticks).front(), "10^-4");
  const auto minors = tick_values(ticks, false);
  ASSERT_EQ(minors.size(), 6u * 8u);
  EXPECT_EQ(minors.front(), 2e-4);
  EXPECT_EQ(minors.back(), 90.0);
  for (const auto& t : ticks) EXPECT_EQ(t.text.empty(), !t.major);
  std::vector<std::string> majors;
  for (const auto& t : ticks) {
    if (t.major) majors.push_back(t.text);
  }
  EXPECT_EQ(majors,
            (std::vector<std::string>{"10^-4", "10^-3", "10^-2", "10^-1", "10^0", "10^1", "10^2"}));
}

TEST(Log10Ticks, WideRangesLabelFewerDecades) {
  const auto ticks = log10_ticks(1e-10, 1e10);  // 20 decades: every 2nd labelled, no 2..9
  std::size_t labelled = 0;
  for (const auto& t : ticks) {
    if (!t.text.empty()) {
      ++labelled;
      EXPECT_TRUE(t.major);
    }
  }
  EXPECT_EQ(labelled, 11u);
  EXPECT_EQ(ticks.size(), 21u);  // every decade still has a (minor) tick
  const auto huge = log10_ticks(1e-300, 1e300);
  EXPECT_LE(huge.size(), 70u);
  EXPECT_GE(huge.size(), 8u);
  for (const auto& t : huge) EXPECT_FALSE(t.text.empty());
}

TEST(Log10Ticks, DegenerateInputs) {
  EXPECT_TRUE(log10_ticks(0.0, 10.0).empty());
  EXPECT_TRUE(log10_ticks(-1.0, 10.0).empty());
  EXPECT_TRUE(log10_ticks(1.0, kNaN).empty());
  const auto one = log10_ticks(1.0, 1.0);  // a decade each side
  EXPECT_EQ(tick_values(one, true), (std::vector<double>{0.1, 1.0, 10.0}));
  EXPECT_EQ(decade_floor(999.9), 100.0);
  EXPECT_EQ(decade_floor(1000.0), 1000.0);
  EXPECT_EQ(decade_ceil(1000.0), 1000.0);
  EXPECT_EQ(decade_ceil(1000.1), 10000.0);
  EXPECT_EQ(decade_floor(1e-300), 1e-300);
}

}  // namespace
}  // namespace imunoise::report
