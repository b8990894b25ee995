// Tests of io/recording_plan_csv.h: plan.csv written and read back to the same plan, its
// columns as a spreadsheet reads them, and located errors for bad files.
#include "io/recording_plan_csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A plan as plan_recording makes it, by hand: two axes, three durations, two targets.
pipeline::RecordingPlan sample_plan() {
  pipeline::RecordingPlan plan;
  plan.rate_hz = 100.0;
  plan.durations_s = {60.0, 3600.0, 86400.0};
  plan.targets = {{NoiseTerm::random_walk, 0.2}, {NoiseTerm::bias_instability, 0.1}};
  for (const char* name : {"gyro_x", "accel_y"}) {
    pipeline::AxisPlan axis;
    axis.name = name;
    axis.identify_duration_s.fill(std::numeric_limits<double>::quiet_NaN());
    axis.target_duration_s.fill(std::numeric_limits<double>::quiet_NaN());
    for (std::size_t d = 0; d < plan.durations_s.size(); ++d) {
      PerTerm<pipeline::TermPrecision> row{};
      for (NoiseTerm t :
           {NoiseTerm::white_noise, NoiseTerm::bias_instability, NoiseTerm::random_walk}) {
        row[t].present = true;
        row[t].identified = d > 0 || t == NoiseTerm::white_noise;
        row[t].relative_halfwidth = row[t].identified ? 0.3 / (1.0 + d) + 1e-3 / 3.0 : kInf;
      }
      axis.table.push_back(row);
    }
    axis.identify_duration_s[NoiseTerm::white_noise] = 60.0;
    axis.identify_duration_s[NoiseTerm::bias_instability] = 231.84654441258718;
    axis.identify_duration_s[NoiseTerm::random_walk] = 3447.371810514869;
    axis.target_duration_s[NoiseTerm::random_walk] =
        std::string(name) == "gyro_x" ? 40037.47 : kInf;
    axis.target_duration_s[NoiseTerm::bias_instability] = 14016.819652953087;
    plan.axes.push_back(axis);
  }
  plan.all_targets_duration_s = kInf;
  return plan;
}

/// Equal to within the rounding of the ×100 of the percent columns.
void expect_same(const pipeline::RecordingPlan& a, const pipeline::RecordingPlan& b) {
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.durations_s, b.durations_s);
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t k = 0; k < a.targets.size(); ++k) {
    EXPECT_EQ(a.targets[k].term, b.targets[k].term);
    EXPECT_NEAR(a.targets[k].relative_halfwidth, b.targets[k].relative_halfwidth, 1e-15);
  }
  EXPECT_EQ(a.all_targets_duration_s, b.all_targets_duration_s);
  ASSERT_EQ(a.axes.size(), b.axes.size());
  for (std::size_t x = 0; x < a.axes.size(); ++x) {
    EXPECT_EQ(a.axes[x].name, b.axes[x].name);
    ASSERT_EQ(a.axes[x].table.size(), b.axes[x].table.size());
    for (std::size_t d = 0; d < a.axes[x].table.size(); ++d) {
      for (NoiseTerm t : kNoiseTerms) {
        const auto& p = a.axes[x].table[d][t];
        const auto& q = b.axes[x].table[d][t];
        EXPECT_EQ(p.present, q.present);
        EXPECT_EQ(p.identified, q.identified);
        if (std::isinf(p.relative_halfwidth)) {
          EXPECT_TRUE(std::isinf(q.relative_halfwidth));
        } else {
          EXPECT_NEAR(p.relative_halfwidth, q.relative_halfwidth, 1e-15);
        }
      }
    }
    for (NoiseTerm t : kNoiseTerms) {
      const double i = a.axes[x].identify_duration_s[t], j = b.axes[x].identify_duration_s[t];
      EXPECT_TRUE(std::isnan(i) ? std::isnan(j) : i == j) << term_symbol(t);
      const double u = a.axes[x].target_duration_s[t], v = b.axes[x].target_duration_s[t];
      EXPECT_TRUE(std::isnan(u) ? std::isnan(v) : u == v) << term_symbol(t);
    }
  }
}

TEST(RecordingPlanCsv, RoundTripsThroughAFile) {
  const pipeline::RecordingPlan plan = sample_plan();
  const auto path = test::make_temp_dir("plan_csv") / "plan.csv";
  write_plan_csv(plan, path.string());
  expect_same(plan, read_plan_csv(path.string()));
}

// Axis names are free text (a mapped column): a comma or a quote in one is quoted on write
// and read back as written.
TEST(RecordingPlanCsv, AxisNamesWithCommasAndQuotesRoundTrip) {
  pipeline::RecordingPlan plan = sample_plan();
  plan.axes[0].name = "gyro, \"left\"";
  const std::string text = format_plan_csv(plan);
  EXPECT_NE(text.find("expected,\"gyro, \"\"left\"\"\",N,"), std::string::npos);
  expect_same(plan, parse_plan_csv(text, "plan.csv"));
  EXPECT_THROW(parse_plan_csv(text.substr(0, text.find("\"\"left")) + "\n", "plan.csv"),
               InputError);
}

TEST(RecordingPlanCsv, ColumnsNameTheirUnitsAndRowsAreFlat) {
  const auto path = test::make_temp_dir("plan_csv_columns") / "plan.csv";
  write_plan_csv(sample_plan(), path.string());
  // Read by the tests' own CSV reader, not io's: what a spreadsheet sees.
  const auto rows = test::read_csv_rows(path);
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], (std::vector<std::string>{"kind", "axis", "term", "rate_hz", "duration_s",
                                               "present", "identified",
                                               "relative_halfwidth_percent", "target_percent"}));
  // 2 axes × 3 durations × 5 terms expected rows, 2 × 3 identify, 2 × 2 target, 2 goals, 1 all.
  EXPECT_EQ(rows.size(), 1u + 30u + 6u + 4u + 2u + 1u);
  EXPECT_EQ(rows[1], (std::vector<std::string>{"expected", "gyro_x", "Q", "100", "60", "0", "0",
                                               "inf", ""}));
  EXPECT_EQ(rows.back(),
            (std::vector<std::string>{"all_targets", "all", "all", "100", "inf", "", "", "", ""}));
}

TEST(RecordingPlanCsv, BadFilesNameFileLineAndProblem) {
  const std::string header =
      "kind,axis,term,rate_hz,duration_s,present,identified,relative_halfwidth_percent,"
      "target_percent\n";
  const auto message = [](const std::string& text) {
    try {
      parse_plan_csv(text, "plan.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("").find("plan.csv: empty file"), std::string::npos);
  EXPECT_NE(message("a,b\n").find("plan.csv:1: unexpected header 'a,b'"), std::string::npos);
  EXPECT_EQ(message(header + "expected,gyro_x,Z,100,60,1,1,2,\n"),
            "plan.csv:2: column 'term': 'Z' is not Q, N, B, K or R");
  EXPECT_EQ(message(header + "expected,gyro_x,N,100,sixty,1,1,2,\n"),
            "plan.csv:2: column 'duration_s': 'sixty' is not a number");
  EXPECT_EQ(message(header + "expected,gyro_x,N,100,60,yes,1,2,\n"),
            "plan.csv:2: column 'present': expected 0 or 1, got 'yes'");
  EXPECT_EQ(message(header + "expected,gyro_x,N,100,60,1,1\n"),
            "plan.csv:2: 7 fields, the header has 9");
  EXPECT_EQ(message(header + "guess,gyro_x,N,100,60,1,1,2,\n"),
            "plan.csv:2: column 'kind': 'guess' is not expected, identify, target, goal or "
            "all_targets");
  EXPECT_EQ(message(header + "expected,gyro_x,N,100,60,1,1,2,\nexpected,gyro_x,N,50,60,1,1,2,\n"),
            "plan.csv:3: column 'rate_hz': differs from line 2");
  // A table with a hole: N at 60 s but no Q, B, K, R.
  EXPECT_EQ(message(header + "expected,gyro_x,N,100,60,1,1,2,\n"),
            "plan.csv: axis gyro_x has no expected row for Q at 60 s");
  EXPECT_EQ(message(header), "plan.csv: no rows (is this a plan.csv written by imunoise plan?)");
  try {
    read_plan_csv("/nonexistent/plan.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/plan.csv: cannot open the plan file");
  }
}

}  // namespace
}  // namespace imunoise::io
