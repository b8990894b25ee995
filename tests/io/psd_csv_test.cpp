// Tests of io/psd_csv.h: a table written and read back is the same table, field by field and
// byte for byte; a bad file is a located InputError.
#include "io/psd_csv.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_support.h"

namespace imunoise::io {
namespace {

PsdAxis axis(const std::string& name, std::vector<double> f, double level) {
  PsdAxis a;
  a.name = name;
  a.psd.frequency_hz = f;
  for (double x : f) {
    a.psd.density.push_back(level / (1.0 + x));
    a.psd.dof.push_back(2.0 + x / 3.0);
    a.model_density.push_back(level * (1.0 + 1e-3 * x));
  }
  return a;
}

TEST(PsdCsv, RoundTripGivesTheSameTableAndTheSameBytes) {
  const auto dir = test::make_temp_dir("psd_csv");
  PsdTable written;
  written.frequency_hz = {0.01, 0.1, 1.0 / 3.0, 10.0};
  // accel_y lacks the lowest bin: an empty cell in its columns.
  written.axes = {axis("gyro_x", {0.01, 0.1, 1.0 / 3.0, 10.0}, 1e-8),
                  axis("accel_y", {0.1, 1.0 / 3.0, 10.0}, 4e-6)};
  write_psd_csv((dir / "psd.csv").string(), written);
  const PsdTable read = read_psd_csv((dir / "psd.csv").string());
  EXPECT_EQ(read.frequency_hz, written.frequency_hz);
  ASSERT_EQ(read.axes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read.axes[i].name, written.axes[i].name);
    EXPECT_EQ(read.axes[i].psd.frequency_hz, written.axes[i].psd.frequency_hz);
    EXPECT_EQ(read.axes[i].psd.density, written.axes[i].psd.density);
    EXPECT_EQ(read.axes[i].psd.dof, written.axes[i].psd.dof);
    EXPECT_EQ(read.axes[i].model_density, written.axes[i].model_density);
  }
  write_psd_csv((dir / "again.csv").string(), read);
  EXPECT_EQ(test::read_file_bytes(dir / "again.csv"), test::read_file_bytes(dir / "psd.csv"));
  const std::string text = test::read_file_bytes(dir / "psd.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "frequency_hz,gyro_x_psd_rad2_per_s2_per_hz,gyro_x_psd_dof,gyro_x_model_psd_rad2_per_"
            "s2_per_hz,accel_y_psd_m2_per_s4_per_hz,accel_y_psd_dof,accel_y_model_psd_m2_per_s4_"
            "per_hz");
}

TEST(PsdCsv, AMissingColumnIsALocatedError) {
  const auto dir = test::make_temp_dir("psd_csv_bad");
  std::ofstream(dir / "psd.csv") << "frequency_hz,gyro_x_psd_rad2_per_s2_per_hz\n0.1,1e-8\n";
  test::expect_throw_containing<InputError>([&] { read_psd_csv((dir / "psd.csv").string()); },
                                            "psd.csv:1: no column 'gyro_x_psd_dof'");
  std::ofstream(dir / "none.csv") << "frequency_hz\n0.1\n";
  test::expect_throw_containing<InputError>([&] { read_psd_csv((dir / "none.csv").string()); },
                                            "none.csv:1: no <axis>_psd_ columns found");
}

}  // namespace
}  // namespace imunoise::io
