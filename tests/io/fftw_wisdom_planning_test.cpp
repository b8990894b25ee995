// Measuring FFTW plans (io/fftw_wisdom_planning): a measured length lands in the process's
// wisdom, where wisdom-only planning finds it and a second call does not measure again; both
// transforms are timed; a length out of range is a caller bug. FFTW wisdom is process-global:
// each test starts and ends with none.
#include "io/fftw_wisdom_planning.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <climits>
#include <mutex>

#include "common/errors.h"
#include "common/fftw_planner_lock.h"

namespace imunoise::io {
namespace {

class FftwWisdomPlanning : public ::testing::Test {
 protected:
  static void forget() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_forget_wisdom();
  }
  void SetUp() override { forget(); }
  void TearDown() override { forget(); }
};

TEST_F(FftwWisdomPlanning, MeasuresOnceThenFindsTheLengthInTheWisdom) {
  const LengthPlanResult first = plan_fft_length(512, PlannerEffort::kMeasure, 0.0);
  EXPECT_FALSE(first.already_known);
  EXPECT_TRUE(first.usable);
  EXPECT_GE(first.planning_s, 0.0);
  EXPECT_GT(first.wisdom_s, 0.0);
  EXPECT_GT(first.estimate_s, 0.0);
  const LengthPlanResult second = plan_fft_length(512, PlannerEffort::kMeasure, 0.0);
  EXPECT_TRUE(second.already_known);
  EXPECT_TRUE(second.usable);
  EXPECT_EQ(second.planning_s, 0.0);
  EXPECT_GT(second.wisdom_s, 0.0);
}

TEST_F(FftwWisdomPlanning, MeasuredWisdomDoesNotCoverPatientPlanning) {
  ASSERT_FALSE(plan_fft_length(256, PlannerEffort::kMeasure, 0.0).already_known);
  // PATIENT is a stricter search than MEASURE: its wisdom-only lookup must not find a
  // measured plan, so the second call searches again.
  const LengthPlanResult patient = plan_fft_length(256, PlannerEffort::kPatient, 0.0);
  EXPECT_FALSE(patient.already_known);
  EXPECT_TRUE(patient.usable);
}

TEST_F(FftwWisdomPlanning, LengthOutOfRangeIsAContractViolation) {
  EXPECT_THROW(plan_fft_length(1, PlannerEffort::kMeasure, 0.0), ContractViolation);
  EXPECT_THROW(plan_fft_length(static_cast<std::size_t>(INT_MAX) + 1, PlannerEffort::kMeasure, 0.0),
               ContractViolation);
}

}  // namespace
}  // namespace imunoise::io
