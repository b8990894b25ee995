/// @file
/// @brief End-to-end test of `imunoise fleet` (issue 23): eleven units simulated by `imunoise
/// simulate` with different parameter draws and analysed by `imunoise analyze` (default
/// intervals), one of them built out of spec; fleet flags that unit and no other, writes
/// fleet.csv (read back by io's reader) and fleet.html with the verdict first; bad input is a
/// clear error and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/fleet_csv.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;

/// PREFIX followed by I, e.g. "unit7" (appended: GCC 12 raises a false -Wstringop-overflow on
/// `"unit" + std::to_string(i)`).
std::string numbered(const char* prefix, int i, const char* suffix = "") {
  std::string s = prefix;
  s.append(std::to_string(i)).append(suffix);
  return s;
}

constexpr int kUnits = 11;
constexpr int kOutOfSpec = 7;

/// The fleet: unit i has N and the accelerometer's N at 0.90 + 0.02·i of nominal (a ±10 %
/// production spread, drawn evenly so no seed decides it), B fixed; unit 7's gyro N is 3× its
/// draw. The spec allows gyro N ≤ 0.15 °/√h and accel N ≤ 90 µg/√Hz: nominal 0.1 °/√h and
/// 60 µg/√Hz.
///
/// Why the verdicts are certain: 20 min at 50 Hz give ν ≈ 6·10⁴ at τ0, so the N interval is
/// ±1.6/√(2ν) ≈ ±0.5 % (theory.md §3.1; measured ±1 % with the interval draws). The largest
/// in-spec draw, 1.10 × 0.1 = 0.11, is 27 % under the limit; unit 7 at 0.312 is 2.1× over it.
/// Why only unit 7 is an N outlier: the draws span log10 ±0.041 around the median (MAD ≈
/// 0.021 for ten evenly spread draws), so their modified z ≤ 0.6745·0.041/0.021 ≈ 1.4 < 3.5,
/// while unit 7 at log10(3) = 0.48 above its draw has z ≈ 15. Other terms (B) scatter by their
/// statistical error alone and are not asserted.
class FleetCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = make_temp_dir("fleet-cli");
    for (int i = 0; i < kUnits; ++i) {
      const double draw = 0.90 + 0.02 * i;
      const double arw = 0.1 * draw * (i == kOutOfSpec ? 3.0 : 1.0);
      const fs::path model = dir_ / numbered("m", i, ".yaml");
      std::ofstream(model) << "name: unit " << i << "\nsample_rate_hz: 50\ngyro:\n"
                           << "  arw_deg_per_sqrt_h: " << arw << "\n"
                           << "  bias_instability_deg_per_h: 5\naccel:\n"
                           << "  vrw_ug_per_sqrt_hz: " << 60.0 * draw << "\n"
                           << "  bias_instability_ug: 20\n";
      const fs::path rec = dir_ / numbered("r", i, ".csv");
      const fs::path out = dir_ / numbered("unit", i);
      std::string simulate = "simulate ";
      simulate.append(model.string()).append(" --duration 20min --seed ");
      simulate.append(std::to_string(100 + i)).append(" -q -o ").append(rec.string());
      auto s = run_imunoise(simulate);
      ASSERT_EQ(s.exit_code, 0) << s.err;
      auto a = run_imunoise("analyze " + rec.string() + " -q -o " + out.string());
      ASSERT_EQ(a.exit_code, 0) << a.err;
      fs::remove(rec);
    }
    std::ofstream(dir_ / "spec.yaml") << "name: test datasheet\ngyro:\n  arw_deg_per_sqrt_h: 0.15\n"
                                      << "accel:\n  vrw_ug_per_sqrt_hz: 90\n";
  }
  static std::string unit_list() {
    std::string s;
    for (int i = 0; i < kUnits; ++i) s.append(" ").append((dir_ / numbered("unit", i)).string());
    return s;
  }
  static fs::path dir_;
};
fs::path FleetCli::dir_;

TEST_F(FleetCli, FlagsTheOutOfSpecUnitAndNoOther) {
  const fs::path out = dir_ / "fleet";
  const auto r = run_imunoise("fleet" + unit_list() + " --spec " + (dir_ / "spec.yaml").string() +
                              " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("imunoise fleet: 11 units against test datasheet: 10 pass, 1 fail, 0 "
                        "undecided\n",
                        0),
            0u)
      << r.out;
  EXPECT_NE(r.out.find("  unit7: fail\n      fails: gyro_x N "), std::string::npos) << r.out;
  const io::FleetTable t = io::read_fleet_csv((out / "fleet.csv").string());
  ASSERT_EQ(t.units.size(), 11u);
  int n_rows = 0;
  for (const pipeline::FleetEntry& e : t.entries) {
    const bool bad = t.units[e.unit] == "unit7";
    if (e.spec_verdict) {
      EXPECT_EQ(*e.spec_verdict, bad && e.sensor == SensorKind::gyro ? pipeline::SpecVerdict::fail
                                                                     : pipeline::SpecVerdict::pass)
          << t.units[e.unit] << " " << e.axis;
      ++n_rows;
    }
    if (e.term == NoiseTerm::white_noise) {
      EXPECT_EQ(e.outlier, bad && e.sensor == SensorKind::gyro)
          << t.units[e.unit] << " " << e.axis << " z " << e.robust_z;
    }
  }
  EXPECT_EQ(n_rows, 11 * 6);  // N of each axis of each unit
  std::ifstream html(out / "fleet.html");
  std::stringstream page;
  page << html.rdbuf();
  const std::string text = page.str();
  const std::size_t header_end = text.find("</header>");
  ASSERT_NE(header_end, std::string::npos);
  EXPECT_EQ(text.find("<section", header_end), text.find("<section id=\"verdict\">"));
  EXPECT_NE(text.find("<table id=\"fleet-units\">"), std::string::npos);
  EXPECT_NE(text.find("<table id=\"fleet-gyro\">"), std::string::npos);
}

TEST_F(FleetCli, WithoutASpecNoVerdictAndBadInputWritesNothing) {
  const fs::path out = dir_ / "fleet-nospec";
  const auto r = run_imunoise("fleet" + unit_list() + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("imunoise fleet: 11 units\n", 0), 0u) << r.out;
  std::ofstream(dir_ / "bad-spec.yaml") << "gyro:\n  arw: 1\n";
  const fs::path none = dir_ / "fleet-bad";
  const auto bad = run_imunoise("fleet" + unit_list() + " --spec " +
                                (dir_ / "bad-spec.yaml").string() + " -o " + none.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad-spec.yaml:2:3: gyro: unknown key 'arw'"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(fs::exists(none));
  const auto missing =
      run_imunoise("fleet " + (dir_ / "nothing").string() + " -o " + none.string());
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_FALSE(fs::exists(none));
}

}  // namespace
}  // namespace imunoise::test
