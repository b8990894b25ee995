// EDF models: theory.md §3.2/§3.3 numbers, GR03 large-J tables against the defining sum,
// the exact white-PM closed form, SP1065 Table 5 / Table 7 and the per-statistic dispatch.
// (Stable32 table rows are checked in stable32_confidence_test.cpp.)
#include "analysis/edf.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "analysis/deviation.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using ::testing::HasSubstr;

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

TEST(Edf, GreenhallReproducesTheoryNumericChecks) {
  // theory.md §3.3 (OADEV): M = 1000, m = 1 → 781 (white FM), 894 (flicker FM).
  EXPECT_NEAR(edf_greenhall(0, 2, 1, 1000, true, false), 781.0, 0.5);
  EXPECT_NEAR(edf_greenhall(-1, 2, 1, 1000, true, false), 894.0, 0.5);
  // White FM, M = 1e4: m = 2 → 5416 (GR03) vs 5712 (SP1065 simple).
  EXPECT_NEAR(edf_greenhall(0, 2, 2, 10000, true, false), 5416.0, 0.5);
  EXPECT_NEAR(edf_simple_oadev(0, 2, 10000), 5712.0, 0.5);
  // m = 100 → 146 vs 148. 146 is the GR03 model summed exactly (F = m, 300 terms); the GR03
  // algorithm uses its Table 2 asymptote here (J = 300 > 100, F → ∞) and gives 147.75.
  EXPECT_NEAR(edf_greenhall_direct(0, 2, 100, 10000, true, false), 146.0, 0.5);
  EXPECT_NEAR(edf_greenhall(0, 2, 100, 10000, true, false), 147.75, 0.01);
  EXPECT_NEAR(edf_simple_oadev(0, 100, 10000), 148.0, 0.5);
}

TEST(Edf, SimpleOadevMatchesTheoryTable) {
  // theory.md §3.2, M = 1000, m = 1: white FM formula 665.1, flicker FM squared form 868
  // (the unsquared allantools transcription would give 0.87).
  EXPECT_NEAR(edf_simple_oadev(0, 1, 1000), 665.1, 0.05);
  EXPECT_NEAR(edf_simple_oadev(-1, 1, 1000), 868.0, 0.5);
  // Hand-evaluated SP1065 Table 5 at M = 1001, m = 10:
  // white PM (1002·981)/(2·991) = 495.9455…; RW FM (999/10)(1000² − 30000 + 400)/998²;
  // flicker FM 5·1001²/(40·1031) = 121.4892…; flicker PM exp(√(ln 50 · ln 5250)).
  EXPECT_NEAR(edf_simple_oadev(2, 10, 1001), 1002.0 * 981.0 / (2.0 * 991.0), 1e-9);
  EXPECT_NEAR(edf_simple_oadev(-2, 10, 1001), 99.9 * 970400.0 / (998.0 * 998.0), 1e-9);
  EXPECT_NEAR(edf_simple_oadev(-1, 10, 1001), 5.0 * 1001.0 * 1001.0 / (40.0 * 1031.0), 1e-9);
  EXPECT_NEAR(edf_simple_oadev(1, 10, 1001), std::exp(std::sqrt(std::log(50.0) * std::log(5250.0))),
              1e-9);
}

TEST(Edf, LargeJTablesAgreeWithDirectSum) {
  // GR03 Tables 1–3 are asymptotes (m → ∞) printed with 3–4 digits; at m = 5000 (J = up to
  // 20000 summands, r ≈ 37) the defining sum must agree within 1e-3 for every tabulated
  // (alpha, d), modified (Table 1) and unmodified (Table 2, with Table 3 for alpha = 1).
  const std::int64_t m = 5000;
  const std::int64_t n_phase = 40 * m;
  for (int d = 1; d <= 3; ++d) {
    for (int alpha = 2; alpha >= -4; --alpha) {
      if (alpha + 2 * d <= 1) continue;
      for (const bool modified : {true, false}) {
        const double table = edf_greenhall(alpha, d, m, n_phase, true, modified);
        const double direct = edf_greenhall_direct(alpha, d, m, n_phase, true, modified);
        EXPECT_LT(rel(table, direct), 1e-3)
            << "alpha=" << alpha << " d=" << d << " modified=" << modified;
      }
    }
  }
}

TEST(Edf, Table2WhitePmRowIsTheExactBinomialSum) {
  // a0 = C(4d,2d)/C(2d,d)², a1 = d/2 (Vandermonde): exact, so it equals the direct sum.
  EXPECT_DOUBLE_EQ(greenhall_table2(2, 1).c0, 1.5);
  EXPECT_DOUBLE_EQ(greenhall_table2(2, 2).c0, 70.0 / 36.0);
  EXPECT_DOUBLE_EQ(greenhall_table2(2, 3).c0, 924.0 / 400.0);
  for (const std::int64_t n_phase : {400, 401, 450, 1000, 100000}) {  // K = ⌈r⌉ ≤ d and > d
    for (const int d : {2, 3}) {
      const double gr = edf_greenhall(2, d, 100, n_phase, true, false);
      const double direct = edf_greenhall_direct(2, d, 100, n_phase, true, false);
      EXPECT_LT(rel(gr, direct), 1e-9) << n_phase << " d=" << d;
    }
  }
}

TEST(Edf, ReducedSumBranchAgreesWithDirectSum) {
  // J > 100 but r = M'/S < d + 1 (the last τ of a record): GR03 keeps 100 summands at stride
  // m' = 100/r. Within 1e-3 of the full sum, except unmodified flicker PM, where GR03
  // evaluates the numerator at F = m' but the Table 3 denominator at F = m: 1.8 % here.
  const std::int64_t m = 1000;
  for (const int alpha : {1, 0, -1, -2}) {
    for (const bool modified : {true, false}) {
      const std::int64_t n_phase = (modified ? 3 : 2) * m + 1500;  // r ≈ 1.5
      const double gr = edf_greenhall(alpha, 2, m, n_phase, true, modified);
      const double direct = edf_greenhall_direct(alpha, 2, m, n_phase, true, modified);
      const double tolerance = (alpha == 1 && !modified) ? 0.02 : 1e-3;
      EXPECT_LT(rel(gr, direct), tolerance) << "alpha=" << alpha << " modified=" << modified;
    }
  }
}

TEST(Edf, GreenhallIsPositiveAndDecreasesWithM) {
  for (const std::int64_t n_phase : {40, 1001, 100001}) {
    for (const DeviationType type : {DeviationType::adev, DeviationType::oadev, DeviationType::mdev,
                                     DeviationType::hdev, DeviationType::ohdev}) {
      const int alpha_min = (type == DeviationType::hdev || type == DeviationType::ohdev) ? -4 : -2;
      for (int alpha = 2; alpha >= alpha_min; --alpha) {
        double previous = INFINITY;
        for (std::int64_t m = 1; 5 * m <= n_phase; m *= 2) {
          const double edf = edf_for(type, alpha, m, n_phase);
          ASSERT_TRUE(std::isfinite(edf) && edf > 0.0) << n_phase << " " << alpha << " " << m;
          EXPECT_LT(edf, previous)
              << static_cast<int>(type) << " M=" << n_phase << " alpha=" << alpha << " m=" << m;
          previous = edf;
        }
      }
    }
  }
}

TEST(Edf, ModifiedAndUnmodifiedCoincideAtMEqualOne) {
  // F = m = 1: MVAR = AVAR, so the EDFs of OADEV and MDEV must be identical.
  for (int alpha = 2; alpha >= -2; --alpha) {
    EXPECT_DOUBLE_EQ(edf_for(DeviationType::oadev, alpha, 1, 1001),
                     edf_for(DeviationType::mdev, alpha, 1, 1001));
  }
}

TEST(Edf, TotdevFollowsSp1065Table7) {
  EXPECT_DOUBLE_EQ(edf_totdev(0, 8, 1001), 1.5 * 1001.0 / 8.0);
  EXPECT_DOUBLE_EQ(edf_totdev(-1, 8, 1001), 1.17 * 1001.0 / 8.0 - 0.22);
  EXPECT_DOUBLE_EQ(edf_totdev(-2, 8, 1001), 0.93 * 1001.0 / 8.0 - 0.36);
  // PM noise: the SP1065 Table 5 simple formula, as Stable32 does.
  EXPECT_DOUBLE_EQ(edf_totdev(1, 8, 19983), edf_simple_oadev(1, 8, 19983));
  EXPECT_DOUBLE_EQ(edf_totdev(2, 8, 19983), edf_simple_oadev(2, 8, 19983));
}

TEST(Edf, EdfForDispatchesPerStatistic) {
  const std::int64_t n = 5000;
  EXPECT_EQ(edf_for(DeviationType::adev, -1, 8, n), edf_greenhall(-1, 2, 8, n, false, false));
  EXPECT_EQ(edf_for(DeviationType::oadev, -1, 8, n), edf_greenhall(-1, 2, 8, n, true, false));
  EXPECT_EQ(edf_for(DeviationType::mdev, -1, 8, n), edf_greenhall(-1, 2, 8, n, true, true));
  EXPECT_EQ(edf_for(DeviationType::tdev, -1, 8, n), edf_greenhall(-1, 2, 8, n, true, true));
  EXPECT_EQ(edf_for(DeviationType::hdev, -3, 8, n), edf_greenhall(-3, 3, 8, n, false, false));
  EXPECT_EQ(edf_for(DeviationType::ohdev, -3, 8, n), edf_greenhall(-3, 3, 8, n, true, false));
  EXPECT_EQ(edf_for(DeviationType::totdev, -1, 8, n), edf_totdev(-1, 8, n));
}

TEST(Edf, RejectsInvalidArguments) {
  try {
    edf_greenhall(-3, 2, 4, 1000, true, false);  // alpha + 2d = 1: AVAR diverges
    ADD_FAILURE() << "no throw";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("edf_greenhall: alpha + 2d must exceed 1"));
  }
  try {
    edf_greenhall(0, 2, 100, 250, true, false);  // L = 201 … fine; modified needs 300
    edf_greenhall(0, 2, 100, 250, true, true);
    ADD_FAILURE() << "no throw";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("edf_greenhall: too few phase samples (M=250, need >= 300"));
  }
  EXPECT_THROW(edf_greenhall(0, 4, 1, 1000, true, false), ContractViolation);
  EXPECT_THROW(edf_greenhall(3, 2, 1, 1000, true, false), AnalysisError);
  EXPECT_THROW(edf_greenhall(0, 2, 0, 1000, true, false), ContractViolation);
  try {
    edf_totdev(-3, 4, 1000);
    ADD_FAILURE() << "no throw";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("edf_totdev: alpha must be in -2..2"));
  }
  EXPECT_THROW(edf_totdev(0, 600, 1000), AnalysisError);  // T/τ < 2
  try {
    edf_simple_oadev(-3, 4, 1000);
    ADD_FAILURE() << "no throw";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("edf_simple_oadev: alpha must be in -2..2"));
  }
  EXPECT_THROW(edf_for(DeviationType::oadev, -4, 2, 1000), AnalysisError);
  EXPECT_THROW(greenhall_table1(-3, 2), AnalysisError);
  EXPECT_THROW(greenhall_table3(0), ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
