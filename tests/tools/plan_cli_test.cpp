/// @file
/// @brief End-to-end test of `imunoise plan` (issue 23 item 2) through the binary: on the
/// datasheet model configs/demo_imu.yaml it prints the plan (the shortest recording meeting
/// every target and the axis that sets it, the per-axis duration table, one expected-precision
/// table per sensor) and writes plan.csv, read here with the test-side CSV reader (not io's):
/// the all_targets row is the longest of the per-axis target rows and names the same axis as
/// the text. The inverse (`--duration`) at the planned duration meets every target and at the
/// longest table duration below it does not. Bad targets are an error naming --target and the
/// item, with exit 2, nothing on stdout and no plan.csv.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;

fs::path demo_model() { return fs::path(IMUNOISE_SOURCE_DIR) / "configs" / "demo_imu.yaml"; }

/// One row of plan.csv by its columns (kind, axis, term, rate_hz, duration_s, present,
/// identified, relative_halfwidth_percent, target_percent).
struct PlanRow {
  std::string kind, axis, term;
  double duration_s = 0.0;
};

/// A plan.csv number: "inf" beyond the searched range, an empty cell (does not apply) NaN.
double number(const std::string& text) {
  if (text.empty()) return std::numeric_limits<double>::quiet_NaN();
  return text == "inf" ? std::numeric_limits<double>::infinity() : std::stod(text);
}

/// K:40 % at 10 Hz: the gyro K needs ≈ 5–6 h (docs/plan.md), a plan of ≈ 7 s of CPU.
class PlanCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = make_temp_dir("plan-cli");
    result_ =
        run_imunoise("plan " + quoted_for_shell(demo_model()) + " --target K:40% --rate 10 -q -o " +
                     quoted_for_shell(dir_ / "plan.csv"));
  }
  static std::vector<PlanRow> rows() {
    const auto table = read_csv_rows(dir_ / "plan.csv");
    std::vector<PlanRow> out;
    if (table.empty()) return out;
    const std::vector<std::string>& header = table.front();
    const auto column = [&](const std::string& name) {
      for (std::size_t k = 0; k < header.size(); ++k) {
        if (header[k] == name) return k;
      }
      ADD_FAILURE() << "plan.csv has no column " << name;
      return std::size_t{0};
    };
    const std::size_t kind = column("kind"), axis = column("axis"), term = column("term"),
                      duration = column("duration_s");
    for (std::size_t r = 1; r < table.size(); ++r) {
      out.push_back({table[r][kind], table[r][axis], table[r][term], number(table[r][duration])});
    }
    return out;
  }
  static fs::path dir_;
  static CommandResult result_;
};
fs::path PlanCli::dir_;
CommandResult PlanCli::result_;

TEST_F(PlanCli, PrintsThePlanAndItsTables) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const std::string& out = result_.out;
  EXPECT_NE(out.find("imunoise plan: " + demo_model().string() + " at 10 Hz"), std::string::npos)
      << out;
  EXPECT_NE(out.find("targets (relative half-width of the 95 % interval): K ±40 %"),
            std::string::npos);
  EXPECT_NE(out.find("shortest recording meeting every target: "), std::string::npos);
  EXPECT_NE(out.find("duration to identify each term / to meet its target"), std::string::npos);
  EXPECT_NE(out.find("gyro: expected relative half-width of the 95 % interval [%]"),
            std::string::npos);
  EXPECT_NE(out.find("accel: expected relative half-width of the 95 % interval [%]"),
            std::string::npos);
  for (const char* axis : {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"}) {
    EXPECT_NE(out.find(std::string("\n") + axis + " "), std::string::npos) << axis;
  }
  EXPECT_NE(out.find("plan.csv: " + (dir_ / "plan.csv").string()), std::string::npos);
  // -q: no informational line on stderr.
  EXPECT_EQ(result_.err, "");
}

TEST_F(PlanCli, PlanCsvHoldsTheDurationsTheTextNames) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const std::vector<PlanRow> table = rows();
  double all = std::numeric_limits<double>::quiet_NaN(), longest = 0.0;
  std::string longest_axis;
  int target_rows = 0, expected_rows = 0;
  for (const PlanRow& r : table) {
    if (r.kind == "all_targets") all = r.duration_s;
    if (r.kind == "expected") ++expected_rows;
    if (r.kind == "target") {
      ++target_rows;
      EXPECT_EQ(r.term, "K");
      if (r.duration_s > longest) {
        longest = r.duration_s;
        longest_axis = r.axis;
      }
    }
  }
  EXPECT_EQ(target_rows, 6);  // every axis of the demo has K
  EXPECT_GT(expected_rows, 6 * 5 * 3);
  ASSERT_TRUE(std::isfinite(all));
  EXPECT_EQ(all, longest);
  // A K:40 % plan of this consumer model is hours, not minutes or days.
  EXPECT_GT(all, 1.0 * 3600.0);
  EXPECT_LT(all, 24.0 * 3600.0);
  EXPECT_NE(result_.out.find("(set by " + longest_axis + " K)"), std::string::npos) << result_.out;
}

TEST_F(PlanCli, InverseMeetsTheTargetsAtThePlannedDurationOnly) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const std::vector<PlanRow> table = rows();
  double all = 0.0, below = 0.0;
  for (const PlanRow& r : table) {
    if (r.kind == "all_targets") all = r.duration_s;
  }
  for (const PlanRow& r : table) {
    if (r.kind == "expected" && r.duration_s < all) below = std::max(below, r.duration_s);
  }
  ASSERT_GT(below, 0.0);
  // The durations as round-trip decimals in seconds: the same sample count as the plan's.
  const auto at = [&](double seconds) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17gs", seconds);
    return run_imunoise("plan " + quoted_for_shell(demo_model()) +
                        " --target K:40% --rate 10 -q --duration " + text);
  };
  const CommandResult met = at(all);
  ASSERT_EQ(met.exit_code, 0) << met.err;
  EXPECT_NE(met.out.find("every target is met"), std::string::npos) << met.out;
  const CommandResult short_of = at(below);
  ASSERT_EQ(short_of.exit_code, 0) << short_of.err;
  EXPECT_NE(short_of.out.find("targets not met: "), std::string::npos) << short_of.out;
}

TEST(PlanCliErrors, BadTargetsAreRefusedWithTheItemAndWriteNothing) {
  const fs::path dir = make_temp_dir("plan-cli-errors");
  const struct {
    const char* target;
    const char* message;
  } cases[] = {
      {"X:20%", "--target: 'X' in 'X:20%' is not a term; expected Q, N, B, K or R"},
      {"K20%", "--target: 'K20%' is not TERM:WIDTH"},
      {"K:abc", "--target: 'K:abc': the width is not a number"},
      {"K:0%", "--target: 'K:0%': the relative half-width must be in (0, 1000 %], got 0 %"},
      {"K:-5%", "--target: 'K:-5%': the relative half-width must be in (0, 1000 %]"},
      {"K:20%,K:10%", "--target: term K is given twice"},
      // The demo model has no ramp on any axis.
      {"R:20%", "--target: no axis of the model has R (ramp); drop that target"},
  };
  for (const auto& c : cases) {
    const fs::path csv = dir / "plan.csv";
    const CommandResult r =
        run_imunoise("plan " + quoted_for_shell(demo_model()) + " --rate 10 -q --target '" +
                     c.target + "' -o " + quoted_for_shell(csv));
    EXPECT_EQ(r.exit_code, 2) << c.target << ": " << r.err;
    EXPECT_NE(r.err.find(std::string("imunoise: error: ") + c.message), std::string::npos)
        << c.target << ": " << r.err;
    EXPECT_EQ(r.out, "") << c.target;
    EXPECT_FALSE(fs::exists(csv)) << c.target;
  }
  // A rate the plan cannot use is refused the same way.
  const CommandResult rate =
      run_imunoise("plan " + quoted_for_shell(demo_model()) + " --rate -3 --target K:20%");
  EXPECT_EQ(rate.exit_code, 2);
  EXPECT_NE(rate.err.find("--rate: expected a rate > 0 Hz, got -3"), std::string::npos) << rate.err;
}

}  // namespace
}  // namespace imunoise::test
