// The NIST SP 1065 test suite: the 1000-point "NBS14" set (built here from its published
// Lehmer generator) and the 9-point set, for every statistic of expected_values.csv.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "analysis/deviation.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using test::nbs14_1000_frequency;
const std::vector<double> kNbs9Frequency = test::nbs9_frequency();

std::optional<DeviationType> type_of(const std::string& statistic) {
  static const std::map<std::string, DeviationType> kTypes = {
      {"ADEV", DeviationType::adev},    {"OADEV", DeviationType::oadev},
      {"MDEV", DeviationType::mdev},    {"TDEV", DeviationType::tdev},
      {"HDEV", DeviationType::hdev},    {"OHDEV", DeviationType::ohdev},
      {"TOTDEV", DeviationType::totdev}};
  const auto it = kTypes.find(statistic);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

TEST(NistSp1065, LehmerGeneratorMatchesPublishedValues) {
  // Published: n[1] = 395529916, n[2] = 1209410747, n[3] = 633705974.
  const auto y = nbs14_1000_frequency();
  EXPECT_DOUBLE_EQ(y[1] * 2147483647.0, 395529916.0);
  EXPECT_DOUBLE_EQ(y[2] * 2147483647.0, 1209410747.0);
  EXPECT_DOUBLE_EQ(y[3] * 2147483647.0, 633705974.0);
}

// Published 7-digit values at relative 5e-7, from rate input and from phase input alike.
TEST(NistSp1065, MatchesNbs14AndNbs9TablesForEveryStatistic) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto rows = test::read_csv_rows(data / "nist-sp1065-nbs" / "expected_values.csv");
  ASSERT_GT(rows.size(), 10u);
  const auto nbs14 = nbs14_1000_frequency();
  const auto nbs14_phase = phase_from_rate(nbs14, 1.0);
  const auto nbs9_phase = phase_from_rate(kNbs9Frequency, 1.0);
  // The same set given as phase (published file) must give the same answers.
  std::vector<double> nbs14_phase_file;
  for (const auto& r : test::read_csv_rows(data / "nist-sp1065-nbs" / "nbs14_1000_phase.csv")) {
    if (r[0] != "index") nbs14_phase_file.push_back(std::stod(r[1]));
  }
  ASSERT_EQ(nbs14_phase_file.size(), 1001u);
  const auto nbs14_phase_detrended = detrended_phase(nbs14_phase_file);

  int checked = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const auto type = type_of(r[1]);
    if (!type) continue;
    const std::int64_t m = std::stoll(r[2]);
    const double published = std::stod(r[4]);
    const bool is_nbs14 = r[0] == "nbs14_1000";
    const auto& phase = is_nbs14 ? nbs14_phase : nbs9_phase;
    const double value = std::sqrt(allan_family_variance(*type, phase, m, 1.0).variance);
    EXPECT_NEAR(value / published, 1.0, 5e-7) << r[0] << " " << r[1] << " m=" << m;
    if (is_nbs14) {
      const double from_phase =
          std::sqrt(allan_family_variance(*type, nbs14_phase_detrended, m, 1.0).variance);
      EXPECT_NEAR(from_phase / value, 1.0, 1e-12) << r[1] << " m=" << m << " (phase input)";
    }
    ++checked;
  }
  EXPECT_EQ(checked, 21 + 14);
}

TEST(NistSp1065, ModifiedAndTimeDeviationAreConsistent) {
  // TDEV = τ·MDEV/√3 (SP 1065 eq. 15) — checked on the NBS14 set at several m.
  const auto phase = phase_from_rate(nbs14_1000_frequency(), 1.0);
  for (std::int64_t m : {1, 3, 7, 50, 200}) {
    const double mdev =
        std::sqrt(allan_family_variance(DeviationType::mdev, phase, m, 1.0).variance);
    const double tdev =
        std::sqrt(allan_family_variance(DeviationType::tdev, phase, m, 1.0).variance);
    EXPECT_NEAR(tdev, static_cast<double>(m) * mdev / std::sqrt(3.0), 1e-14 * tdev) << m;
  }
}

}  // namespace
}  // namespace imunoise::analysis
