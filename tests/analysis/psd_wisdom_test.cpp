// WelchEstimator's FFT plan: from imported FFTW wisdom (FFTW_MEASURE or better) when the
// process holds it, else FFTW_ESTIMATE; the two give the same spectrum up to rounding. Also
// the automatic segment-length rule. FFTW wisdom is process-global: every test here starts
// and ends with no wisdom (fftw_forget_wisdom under the planner mutex), so none depends on
// the order the tests run in, nor leaves wisdom to the other suites of this executable.
#include <fftw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/psd.h"
#include "common/errors.h"
#include "common/fftw_planner_lock.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

void forget_wisdom() {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_forget_wisdom();
}

/// Measures an r2c plan of LENGTH (FFTW_MEASURE: well under a second at 1024), then keeps only
/// its wisdom, exported and imported back as a wisdom file would be.
void import_measured_wisdom(std::size_t length) {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  double* in = static_cast<double*>(fftw_malloc(sizeof(double) * length));
  auto* out = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (length / 2 + 1)));
  ASSERT_NE(in, nullptr);
  ASSERT_NE(out, nullptr);
  fftw_plan plan = fftw_plan_dft_r2c_1d(static_cast<int>(length), in, out, FFTW_MEASURE);
  ASSERT_NE(plan, nullptr);
  fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  char* text = fftw_export_wisdom_to_string();
  ASSERT_NE(text, nullptr);
  const std::string wisdom(text);
  std::free(text);
  fftw_forget_wisdom();
  ASSERT_NE(fftw_import_wisdom_from_string(wisdom.c_str()), 0);
}

class WelchWisdom : public ::testing::Test {
 protected:
  void SetUp() override { forget_wisdom(); }
  void TearDown() override { forget_wisdom(); }
};

TEST_F(WelchWisdom, PlanFromImportedWisdomGivesTheEstimatePlanSpectrum) {
  const std::vector<double> x = test::white_noise(16384, 0.3, 11);
  WelchOptions options;
  options.segment_length = 1024;
  options.detrend = Detrend::none;  // every bin, DC included, well above rounding
  // The reference first: an ESTIMATE plan uses any wisdom the process holds.
  Spectrum reference;
  {
    WelchEstimator estimate_plan(1024, options);
    EXPECT_FALSE(estimate_plan.planned_from_wisdom());
    reference = estimate_plan.estimate(x, 100.0);
  }
  import_measured_wisdom(1024);
  WelchEstimator wisdom_plan(1024, options);
  EXPECT_TRUE(wisdom_plan.planned_from_wisdom());
  const Spectrum s = wisdom_plan.estimate(x, 100.0);
  ASSERT_EQ(s.density.size(), reference.density.size());
  EXPECT_EQ(s.segments, reference.segments);
  // The plans differ only in the order of the butterflies: a few roundings per bin.
  for (std::size_t j = 0; j < s.density.size(); ++j) {
    ASSERT_GT(reference.density[j], 0.0) << "bin " << j;
    EXPECT_LE(std::abs(s.density[j] - reference.density[j]) / reference.density[j], 1e-12)
        << "bin " << j;
  }
  EXPECT_DOUBLE_EQ(s.sample_variance, reference.sample_variance);
  EXPECT_NEAR(s.integrated_power / reference.integrated_power, 1.0, 1e-12);

  // Wisdom for 1024 says nothing about another length.
  const WelchEstimator other(2048, {});
  EXPECT_FALSE(other.planned_from_wisdom());
}

TEST_F(WelchWisdom, EstimatePlansLeaveNoWisdomThatCounts) {
  // An ESTIMATE plan records wisdom of ESTIMATE rigour only: the next estimator of that length
  // must not take it for measured wisdom.
  const WelchEstimator first(512, {});
  EXPECT_FALSE(first.planned_from_wisdom());
  const WelchEstimator second(512, {});
  EXPECT_FALSE(second.planned_from_wisdom());
}

TEST_F(WelchWisdom, WelchPsdUsesTheWisdomOfItsAutomaticLength) {
  // 8192 samples: automatic L = 1024. welch_psd plans through WelchEstimator, so it gets the
  // wisdom too; its result equals the estimator's.
  const std::vector<double> x = test::white_noise(8192, 1.0, 5);
  import_measured_wisdom(automatic_segment_length(x.size()));
  WelchEstimator estimator(1024, {});
  EXPECT_TRUE(estimator.planned_from_wisdom());
  const Spectrum direct = estimator.estimate(x, 10.0);
  const Spectrum one_shot = welch_psd(x, 10.0);
  EXPECT_EQ(one_shot.segment_length, 1024u);
  EXPECT_EQ(one_shot.density, direct.density);
}

TEST(Welch, AutomaticSegmentLengthIsTheLargestPowerOfTwoUpToAnEighth) {
  EXPECT_EQ(automatic_segment_length(16), 16u);
  EXPECT_EQ(automatic_segment_length(255), 16u);  // 255/8 = 31 → 16
  EXPECT_EQ(automatic_segment_length(256), 32u);  // 256/8 = 32
  EXPECT_EQ(automatic_segment_length(10000), 1024u);
  EXPECT_EQ(automatic_segment_length(86'400'000), std::size_t{1} << 23);  // 24 h at 1 kHz
  test::expect_throw_containing<ContractViolation>([] { (void)automatic_segment_length(15); },
                                                   "too short");
  // welch_psd resolves segment_length = 0 by the same rule.
  EXPECT_EQ(welch_psd(test::white_noise(10000, 1.0, 2), 1.0).segment_length, 1024u);
}

}  // namespace
}  // namespace imunoise::analysis
