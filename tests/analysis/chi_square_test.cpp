// Chi-square CDF / quantiles against closed forms (dof 1, 2, 4 and even-dof Poisson sums),
// an independently computed normal quantile (Wilson–Hilferty at huge dof) and round trips
// from dof 1e-2 to 1e7.
#include "analysis/chi_square.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using ::testing::HasSubstr;

/// Relative difference |a − b| / |b|.
double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

/// Standard normal quantile by bisection on std::erfc: slow, but independent of the code
/// under test and accurate to ~1e-15.
double normal_quantile(double p) {
  double lo = -40.0;
  double hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

/// ln Pr(χ²_ν > x) for even ν = 2k: ln[e^{−y} Σ_{j<k} y^j/j!], y = x/2 (Poisson sum),
/// summed downwards from the j = k−1 term so nothing underflows for large ν.
double even_dof_log_survival(double x, int dof) {
  const double y = 0.5 * x;
  const int k = dof / 2;
  double term = 1.0;  // t_j / t_{k−1}
  double sum = 1.0;
  for (int j = k - 1; j > 0; --j) {
    term *= j / y;
    sum += term;
  }
  return -y + (k - 1) * std::log(y) - std::lgamma(static_cast<double>(k)) + std::log(sum);
}

TEST(ChiSquare, QuantileMatchesClosedFormForTwoDof) {
  // χ²_2 is exponential with mean 2: quantile −2 ln(1 − p), upper quantile −2 ln(tail).
  for (const double p : {1e-300, 1e-10, 1e-3, 0.1585, 0.5, 0.8415, 0.999}) {
    EXPECT_LT(rel(chi_square_quantile(p, 2.0), -2.0 * std::log1p(-p)), 1e-13) << p;
    EXPECT_LT(rel(chi_square_upper_quantile(p, 2.0), -2.0 * std::log(p)), 1e-13) << p;
  }
}

TEST(ChiSquare, CdfAndQuantileMatchErfForOneDof) {
  // χ²_1 = Z²: CDF(x) = erf(√(x/2)).
  for (const double x : {1e-12, 1e-4, 0.04, 0.455, 1.0, 2.0, 6.6, 20.0}) {
    EXPECT_LT(rel(chi_square_cdf(x, 1.0), std::erf(std::sqrt(0.5 * x))), 1e-13) << x;
    EXPECT_LT(rel(chi_square_sf(x, 1.0), std::erfc(std::sqrt(0.5 * x))), 1e-12) << x;
  }
  for (const double p : {1e-8, 0.01, 0.1585, 0.5, 0.8415, 0.99}) {
    const double q = chi_square_quantile(p, 1.0);
    // erf has slope ≤ 2/√π, so a 1e-12 relative error in q moves erf by < 1e-12·p·O(1).
    EXPECT_LT(rel(std::erf(std::sqrt(0.5 * q)), p), 1e-12) << p;
  }
}

TEST(ChiSquare, CdfMatchesClosedFormForFourDofIncludingFarTail) {
  // χ²_4: Q(x) = e^{−y}(1 + y), y = x/2; at x = 1000 it is ~1e-215, far below epsilon.
  // P(x) = e^{−y} Σ_{k≥2} y^k/k! (series: 1 − Q cancels for small x).
  for (const double x : {1e-6, 0.3, 1.0, 3.36, 10.0, 40.0, 200.0, 1000.0}) {
    const double y = 0.5 * x;
    const double q = std::exp(-y) * (1.0 + y);
    EXPECT_LT(rel(chi_square_sf(x, 4.0), q), 1e-12) << x;
    double p = 1.0 - q;
    if (y < 1.0) {
      double term = y;
      p = 0.0;
      for (int k = 2; k < 40; ++k) p += (term *= y / k);
      p *= std::exp(-y);
    }
    EXPECT_LT(rel(chi_square_cdf(x, 4.0), p), 1e-13) << x;
  }
}

TEST(ChiSquare, QuantilesMatchPoissonSumForEvenDof) {
  // Independent truth for integer dof up to 2000: invert the Poisson sum by bisection.
  for (const int dof : {6, 10, 50, 200, 2000}) {
    for (const double tail : {1e-6, 0.1585, 0.5, 0.8415}) {
      double lo = 0.0;
      double hi = 10.0 * dof + 100.0;
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (even_dof_log_survival(mid, dof) > std::log(tail) ? lo : hi) = mid;
      }
      EXPECT_LT(rel(chi_square_upper_quantile(tail, dof), 0.5 * (lo + hi)), 1e-12)
          << dof << " " << tail;
    }
  }
}

TEST(ChiSquare, QuantileInvertsCdfFromTinyToHugeDof) {
  // Round trip: CDF(q·(1 ∓ 1e-11)) brackets p, i.e. q is right to 1e-11 relative (for
  // dof ≥ 1e6 the sensitivity of the CDF to q is ≥ 1e-9 per 1e-11, far above its error).
  for (const double dof : {1e-2, 0.1, 0.5, 1.0, 3.7, 10.0, 100.0, 781.3, 1e4, 1e5, 1e6, 1e7}) {
    for (const double p : {1e-6, 0.0015, 0.1585, 0.5, 0.8415, 0.9985}) {
      const double q = chi_square_quantile(p, dof);
      ASSERT_TRUE(std::isfinite(q)) << dof << " " << p;
      ASSERT_GE(q, 0.0);
      if (q < 1e-290) continue;  // true quantile below the double range (tiny dof)
      EXPECT_LE(chi_square_cdf(q * (1.0 - 1e-11), dof), p) << dof << " " << p;
      EXPECT_GE(chi_square_cdf(q * (1.0 + 1e-11), dof), p) << dof << " " << p;
      // Same point from the other tail. Skipped for p = 1e-6, where 1 − p itself carries a
      // 1e-10 relative error in p (the reason chi_square_upper_quantile exists).
      if (p < 1e-3) continue;
      const double upper = chi_square_upper_quantile(1.0 - p, dof);
      EXPECT_LT(rel(upper, q), 1e-12) << dof << " " << p;
    }
  }
}

TEST(ChiSquare, HugeDofDiffersFromWilsonHilfertyOnlyByItsOwnError) {
  // Wilson–Hilferty, ν(1 − 2/(9ν) + z√(2/(9ν)))³, has a relative error c(z)·ν^{-3/2}
  // (+ O(ν^{-2})). If our quantile is exact, (q − q_WH)/q · ν^{3/2} must be the same
  // constant at ν = 1e5, 1e6, 1e7 (0.45 at |z| = 3, 0.05 at |z| = 1); an error of ours of
  // 3e-13 relative at ν = 1e7 would already move it by 0.01.
  for (const double p : {0.0015, 0.1585, 0.8415, 0.9985}) {
    const double z = normal_quantile(p);
    double previous = std::numeric_limits<double>::quiet_NaN();
    for (const double dof : {1e5, 1e6, 1e7}) {
      const double w = 1.0 - 2.0 / (9.0 * dof) + z * std::sqrt(2.0 / (9.0 * dof));
      const double q = chi_square_quantile(p, dof);
      const double scaled = (q - dof * w * w * w) / q * std::pow(dof, 1.5);
      EXPECT_LT(std::fabs(scaled), 0.5) << dof << " " << p;
      if (!std::isnan(previous)) {
        EXPECT_NEAR(scaled, previous, 0.01) << dof << " " << p;
      }
      previous = scaled;
    }
  }
}

TEST(ChiSquare, TinyDofGivesFiniteQuantilesOrUnderflowToZero) {
  // dof = 0.01: P(0.005, y) ≈ y^0.005/Γ(1.005), so the 1 % quantile is ~1e-400 (→ 0) and
  // the median ~7e-61; nothing may be NaN.
  EXPECT_EQ(chi_square_quantile(0.01, 0.01), 0.0);
  const double median = chi_square_quantile(0.5, 0.01);
  EXPECT_GT(median, 1e-62);
  EXPECT_LT(median, 1e-59);
  EXPECT_LT(rel(chi_square_cdf(median, 0.01), 0.5), 1e-13);
  EXPECT_TRUE(std::isfinite(chi_square_quantile(0.99, 0.01)));
}

TEST(ChiSquare, QuantilesAreMonotoneInProbabilityAndDof) {
  for (const double dof : {0.3, 7.0, 420.0, 3e5}) {
    double previous = 0.0;
    for (double p = 0.01; p < 1.0; p += 0.01) {
      const double q = chi_square_quantile(p, dof);
      EXPECT_GT(q, previous) << dof << " " << p;
      previous = q;
    }
  }
  // Pr(χ²_ν ≤ x) decreases with ν at fixed x.
  EXPECT_GT(chi_square_cdf(50.0, 40.0), chi_square_cdf(50.0, 41.5));
}

TEST(ChiSquare, ExtremeDofFinishQuickly) {
  const auto start = std::chrono::steady_clock::now();
  for (const double dof : {1e-2, 1e7, 1e9}) {
    for (const double p : {1e-12, 0.5, 1.0 - 1e-12}) {
      EXPECT_TRUE(std::isfinite(chi_square_quantile(p, dof)));
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 2.0);
}

TEST(ChiSquare, RejectsInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double p : {0.0, 1.0, -0.1, 1.5, nan}) {
    try {
      chi_square_quantile(p, 3.0);
      ADD_FAILURE() << "no throw for p=" << p;
    } catch (const ContractViolation& e) {
      EXPECT_THAT(e.what(), HasSubstr("chi_square_quantile: probability must be in (0, 1)"));
    }
  }
  for (const double dof : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    try {
      chi_square_quantile(0.5, dof);
      ADD_FAILURE() << "no throw for dof=" << dof;
    } catch (const AnalysisError& e) {
      EXPECT_THAT(e.what(), HasSubstr("chi_square_quantile: dof must be finite and > 0"));
    }
  }
  EXPECT_THROW(chi_square_upper_quantile(0.0, 3.0), ContractViolation);
  try {
    chi_square_cdf(-1.0, 3.0);
    ADD_FAILURE() << "no throw for x=-1";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), HasSubstr("argument must be finite and >= 0"));
  }
  EXPECT_THROW(chi_square_sf(1.0, 0.0), AnalysisError);
  EXPECT_THROW(regularized_gamma_p(-2.0, 1.0), AnalysisError);
}

}  // namespace
}  // namespace imunoise::analysis
