#include "analysis/tau_grid.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(TauGrid, OctaveStopsAtStopRatio) {
  // OADEV stop ratio 4: M = 1001 → m ≤ 250.
  const auto m = averaging_factors(parse_tau_grid("octave"), DeviationType::oadev, 1001);
  EXPECT_THAT(m, ElementsAre(1, 2, 4, 8, 16, 32, 64, 128));
  EXPECT_EQ(max_averaging_factor(DeviationType::oadev, 1001), 250);
  EXPECT_EQ(max_averaging_factor(DeviationType::adev, 1001), 200);
  EXPECT_EQ(max_averaging_factor(DeviationType::totdev, 1001), 500);
}

TEST(TauGrid, DecadeIsOneTwoFourPerDecade) {
  const auto m = averaging_factors(parse_tau_grid("decade"), DeviationType::oadev, 100000);
  EXPECT_THAT(m, ElementsAre(1, 2, 4, 10, 20, 40, 100, 200, 400, 1000, 2000, 4000, 10000, 20000));
}

TEST(TauGrid, LogGridIsRoundedAndDeduplicated) {
  const auto m = averaging_factors(parse_tau_grid("log:10"), DeviationType::oadev, 400);
  // round(10^(i/10)): 1 1 2 2 3 3 4 5 6 8 10 13 16 20 25 32 40 50 63 79 100
  EXPECT_THAT(m, ElementsAre(1, 2, 3, 4, 5, 6, 8, 10, 13, 16, 20, 25, 32, 40, 50, 63, 79, 100));
}

TEST(TauGrid, AllGridListsEveryFactor) {
  const auto m = averaging_factors(parse_tau_grid("all"), DeviationType::hdev, 26);
  EXPECT_THAT(m, ElementsAre(1, 2, 3, 4, 5));
}

TEST(TauGrid, ExplicitListIsSortedAndUnique) {
  const auto spec = parse_tau_grid("10,1,2,10");
  EXPECT_THAT(averaging_factors(spec, DeviationType::oadev, 1000), ElementsAre(1, 2, 10));
  EXPECT_EQ(to_string(spec), "1,2,10");
}

TEST(TauGrid, ExplicitFactorBeyondRecordIsAClearError) {
  try {
    averaging_factors(parse_tau_grid("1,300"), DeviationType::oadev, 1001);
    FAIL() << "expected AnalysisError";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("too few samples for the requested tau"));
    EXPECT_THAT(e.what(), HasSubstr("m = 300"));
    EXPECT_THAT(e.what(), HasSubstr("largest usable m is 250"));
  }
}

TEST(TauGrid, RecordTooShortForAnyTauIsAClearError) {
  EXPECT_THROW(averaging_factors(parse_tau_grid("octave"), DeviationType::oadev, 3), AnalysisError);
  EXPECT_NO_THROW(averaging_factors(parse_tau_grid("octave"), DeviationType::oadev, 4));
}

TEST(TauGrid, AllGridOnLongRecordIsRefusedNotHung) {
  EXPECT_THROW(averaging_factors(parse_tau_grid("all"), DeviationType::oadev, 10'000'000),
               AnalysisError);
}

TEST(TauGrid, MalformedSpecsAreInputErrors) {
  for (const char* bad :
       {"", "log:", "log:0", "log:x", "1,,2", "0", "-3", "octaves", "1.5", "log:100000"}) {
    EXPECT_THROW(parse_tau_grid(bad), InputError) << bad;
  }
}

TEST(TauGrid, TermCountsFollowEstimatorDefinitions) {
  // Stable32 "#" column on PHASE.DAT (M = 1001): ADEV m=197 → 4, HDEV m=197 → 3,
  // OADEV m=239 → 523, TOTDEV → M − 2.
  EXPECT_EQ(estimator_term_count(DeviationType::adev, 1001, 197), 4);
  EXPECT_EQ(estimator_term_count(DeviationType::hdev, 1001, 197), 3);
  EXPECT_EQ(estimator_term_count(DeviationType::oadev, 1001, 239), 523);
  EXPECT_EQ(estimator_term_count(DeviationType::mdev, 1001, 10), 972);
  EXPECT_EQ(estimator_term_count(DeviationType::ohdev, 1001, 10), 971);
  EXPECT_EQ(estimator_term_count(DeviationType::totdev, 1001, 499), 999);
}

TEST(TauGrid, Theo1GridsUseEvenFactorsUpToMMinusOne) {
  // Stable32's PHASE.DAT Thêo1 table (M = 1001) runs to AF 998; m ≤ M − 1 and even.
  EXPECT_EQ(max_averaging_factor(DeviationType::theo1, 1001), 1000);
  EXPECT_EQ(max_averaging_factor(DeviationType::theo1, 1000), 998);
  EXPECT_THAT(averaging_factors(parse_tau_grid("decade"), DeviationType::theo1, 1001),
              ElementsAre(2, 4, 10, 20, 40, 100, 200, 400, 1000));
  EXPECT_THAT(averaging_factors(parse_tau_grid("octave"), DeviationType::theo1, 100),
              ElementsAre(2, 4, 8, 16, 32, 64));
  EXPECT_THROW(averaging_factors(parse_tau_grid("2,3"), DeviationType::theo1, 100), AnalysisError);
}

TEST(TauGrid, TotalFamilyStopsAtOneThird) {
  EXPECT_EQ(max_averaging_factor(DeviationType::mtotdev, 1001), 333);
  EXPECT_EQ(max_averaging_factor(DeviationType::htotdev, 1001), 333);
  EXPECT_EQ(estimator_term_count(DeviationType::mtotdev, 1001, 332), 6);
}

TEST(TauGrid, QuadraticCostStatisticsRefuseHugeWork) {
  EXPECT_THROW(averaging_factors(parse_tau_grid("log:10"), DeviationType::mtotdev, 1'000'000),
               AnalysisError);
  EXPECT_NO_THROW(averaging_factors(parse_tau_grid("1,10,100"), DeviationType::mtotdev, 1'000'000));
}

}  // namespace
}  // namespace imunoise::analysis
