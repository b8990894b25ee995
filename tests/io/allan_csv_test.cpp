// Tests of io/allan_csv.h: a table written and read back is the same table, field by field
// and byte for byte; a bad file is a located InputError.
#include "io/allan_csv.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_support.h"

namespace imunoise::io {
namespace {

analysis::DeviationPoint point(std::int64_t m, double tau0_s, double value, double edf, int alpha) {
  analysis::DeviationPoint p;
  p.m = m;
  p.tau_s = static_cast<double>(m) * tau0_s;
  p.value = value;
  p.ci_low = 0.9 * value;
  p.ci_high = 1.1 * value;
  p.edf = edf;
  p.alpha = alpha;
  return p;
}

/// Two axes of two sensors; gyro_z lacks an OADEV point at m = 4 and accel_x has no OHDEV at
/// m = 1, so the file has empty cells.
AllanTable example_table() {
  const double tau0_s = 0.01;
  AllanTable t;
  t.m = {1, 2, 4};
  for (std::int64_t m : t.m) t.tau_s.push_back(static_cast<double>(m) * tau0_s);
  AllanAxis gyro{"gyro_z", {}, {}, {1.0 / 3.0, 2e-4, 1.5e-4}};
  gyro.oadev.points = {point(1, tau0_s, 3.0e-3, 1234.5, 0), point(2, tau0_s, 2.1e-3, 600.25, -1)};
  gyro.ohdev.points = {point(1, tau0_s, 3.1e-3, 0, 0), point(2, tau0_s, 2.2e-3, 0, 0),
                       point(4, tau0_s, 1.6e-3, 0, 0)};
  AllanAxis accel{"accel_x", {}, {}, {5e-3, 4e-3, 3e-3}};
  accel.oadev.points = {point(1, tau0_s, 5.1e-3, 99.0, 2), point(2, tau0_s, 4.2e-3, 45.5, 1),
                        point(4, tau0_s, 3.3e-3, 20.0, -2)};
  accel.ohdev.points = {point(2, tau0_s, 4.3e-3, 0, 0), point(4, tau0_s, 0.1 + 0.2, 0, 0)};
  t.axes = {gyro, accel};
  return t;
}

void expect_same_points(const analysis::DeviationCurve& a, const analysis::DeviationCurve& b,
                        bool with_edf) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].m, b.points[i].m);
    EXPECT_EQ(a.points[i].tau_s, b.points[i].tau_s);
    EXPECT_EQ(a.points[i].value, b.points[i].value);
    EXPECT_EQ(a.points[i].ci_low, b.points[i].ci_low);
    EXPECT_EQ(a.points[i].ci_high, b.points[i].ci_high);
    if (with_edf) {
      EXPECT_EQ(a.points[i].edf, b.points[i].edf);
      EXPECT_EQ(a.points[i].alpha, b.points[i].alpha);
    }
  }
}

TEST(AllanCsv, RoundTripGivesTheSameTableAndTheSameBytes) {
  const auto dir = test::make_temp_dir("allan_csv");
  const AllanTable written = example_table();
  write_allan_csv((dir / "allan.csv").string(), written);
  const AllanTable read = read_allan_csv((dir / "allan.csv").string(), 0.95);
  EXPECT_EQ(read.m, written.m);
  EXPECT_EQ(read.tau_s, written.tau_s);
  ASSERT_EQ(read.axes.size(), 2u);
  // Read in channel order (gyro before accel), whatever the column order.
  const AllanAxis* axes[] = {&written.axes[0], &written.axes[1]};
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read.axes[i].name, axes[i]->name);
    EXPECT_EQ(read.axes[i].model_adev, axes[i]->model_adev);
    expect_same_points(read.axes[i].oadev, axes[i]->oadev, true);
    expect_same_points(read.axes[i].ohdev, axes[i]->ohdev, false);
    EXPECT_EQ(read.axes[i].oadev.type, analysis::DeviationType::oadev);
    EXPECT_EQ(read.axes[i].ohdev.type, analysis::DeviationType::ohdev);
    EXPECT_EQ(read.axes[i].oadev.confidence, 0.95);
  }
  write_allan_csv((dir / "again.csv").string(), read);
  EXPECT_EQ(test::read_file_bytes(dir / "again.csv"), test::read_file_bytes(dir / "allan.csv"));
  const std::string text = test::read_file_bytes(dir / "allan.csv");
  EXPECT_EQ(text.substr(0, text.find(',', text.find("gyro_z_oadev_rad_per_s"))),
            "m,tau_s,gyro_z_oadev_rad_per_s");
  EXPECT_NE(text.find("accel_x_ohdev_ci_high_m_per_s2"), std::string::npos);
}

TEST(AllanCsv, AMissingColumnOrEmptyCellIsALocatedError) {
  const auto dir = test::make_temp_dir("allan_csv_bad");
  write_allan_csv((dir / "allan.csv").string(), example_table());
  std::string text = test::read_file_bytes(dir / "allan.csv");
  const std::string renamed = "gyro_z_oadev_edf";
  {
    std::string t = text;
    t.replace(t.find(renamed), renamed.size(), "gyro_z_oadev_dof");
    std::ofstream(dir / "renamed.csv") << t;
  }
  test::expect_throw_containing<InputError>(
      [&] { read_allan_csv((dir / "renamed.csv").string(), 0.95); },
      "renamed.csv:1: no column 'gyro_z_oadev_edf'");
  {
    // Line 2: clear the first OADEV interval cell (the 4th field).
    std::string t = text;
    const std::size_t line2 = t.find('\n') + 1;
    std::size_t cell = line2;
    for (int i = 0; i < 3; ++i) cell = t.find(',', cell) + 1;
    t.erase(cell, t.find(',', cell) - cell);
    std::ofstream(dir / "hole.csv") << t;
  }
  test::expect_throw_containing<InputError>(
      [&] { read_allan_csv((dir / "hole.csv").string(), 0.95); },
      "hole.csv:2: empty cell in column 'gyro_z_oadev_ci_low_rad_per_s'");
  std::ofstream(dir / "none.csv") << "m,tau_s\n1,0.01\n";
  test::expect_throw_containing<InputError>(
      [&] { read_allan_csv((dir / "none.csv").string(), 0.95); }, "none.csv:1: no <axis>_oadev_");
}

}  // namespace
}  // namespace imunoise::io
