/// @file
/// @brief EDF models (see edf.h). References:
/// [GR03] C. A. Greenhall, W. J. Riley, "Uncertainty of stability variances based on finite
///        differences", Proc. 35th PTTI, 2003 — eqs. (7)–(10), (13), Tables 1–3, and the
///        four-case algorithm; case structure as in Riley's Stable32 code "CombinedEDF"
///        (public source k2hrt/edf, read for facts, not copied).
/// [SP1065] W. J. Riley, NIST SP 1065, 2008 — Table 5 (simple OADEV EDF), Table 7 (TOTDEV).
#include "analysis/edf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using Real = long double;  // the F² scaling of s_x (F up to m) cancels ~2·log10(m) digits

constexpr Real kInfiniteF = std::numeric_limits<Real>::infinity();
constexpr std::int64_t kJmax = 100;  // GR03: direct summation limit

/// Generalized autocovariance of the power-law phase "increment" process, GR03 eq. (7):
/// −|t| (α=2), t²ln|t| (1), |t|³ (0), t⁴ln|t| (−1), |t|⁵ (−2), t⁶ln|t| (−3), |t|⁷ (−4).
/// (Only squares of s_z enter the EDF, so the overall sign convention is irrelevant.)
Real s_w(Real t, int alpha) {
  const Real a = std::fabs(t);
  switch (alpha) {
    case 2:
      return -a;
    case 1:
      return a == 0 ? 0 : t * t * std::log(a);
    case 0:
      return a * a * a;
    case -1:
      return a == 0 ? 0 : t * t * t * t * std::log(a);
    case -2:
      return a * a * a * a * a;
    case -3:
      return a == 0 ? 0 : t * t * t * t * t * t * std::log(a);
    case -4:
      return a * a * a * a * a * a * a;
    default:
      throw AnalysisError("edf_greenhall: alpha must be in -4..2 (got " + std::to_string(alpha) +
                          ")");
  }
}

/// Phase autocovariance after the F-point moving average, GR03 eq. (8); F = ∞ is the
/// continuous limit s_w(t; α+2) (used for unmodified variances at large m, α ≤ 0).
Real s_x(Real t, Real f, int alpha) {
  if (std::isinf(f)) return s_w(t, alpha + 2);
  return f * f * (2 * s_w(t, alpha) - s_w(t - 1 / f, alpha) - s_w(t + 1 / f, alpha));
}

/// Autocovariance of the d-th differences at lag t (in units of τ), GR03 eq. (9): binomial
/// weights (2; −1,−1), (6; −4,−4; 1,1), (20; −15,−15; 6,6; −1,−1) at offsets 0, ±1, ±2, ±3.
Real s_z(Real t, Real f, int alpha, int d) {
  static constexpr std::array<std::array<int, 4>, 3> kWeights = {
      {{2, -1, 0, 0}, {6, -4, 1, 0}, {20, -15, 6, -1}}};
  const auto& w = kWeights[static_cast<std::size_t>(d - 1)];
  Real sum = w[0] * s_x(t, f, alpha);
  for (int k = 1; k <= d; ++k)
    sum += w[static_cast<std::size_t>(k)] * (s_x(t - k, f, alpha) + s_x(t + k, f, alpha));
  return sum;
}

/// GR03 eq. (10): s_z(0)² + (1 − J/M) s_z(J/S)² + 2 Σ_{j=1}^{J−1} (1 − j/M) s_z(j/S)².
Real basic_sum(std::int64_t j_count, Real m_count, Real s, Real f, int alpha, int d) {
  const Real z0 = s_z(0, f, alpha, d);
  Real sum = z0 * z0;
  for (std::int64_t j = 1; j < j_count; ++j) {
    const Real z = s_z(static_cast<Real>(j) / s, f, alpha, d);
    sum += 2 * (1 - static_cast<Real>(j) / m_count) * z * z;
  }
  const Real zj = s_z(static_cast<Real>(j_count) / s, f, alpha, d);
  sum += (1 - static_cast<Real>(j_count) / m_count) * zj * zj;
  return sum;
}

/// Binomial coefficient C(n, k) for the small n (≤ 6) used here.
double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

/// The quantities shared by all GR03 cases.
struct GreenhallSetup {
  Real f;                ///< filter factor F: 1 (modified) or m (unmodified)
  Real s;                ///< stride factor S: m (overlapping) or 1
  std::int64_t m_terms;  ///< M' = 1 + ⌊S(M − L)/m⌋, the number of d-th differences
  std::int64_t j;        ///< J = min(M', (d+1)S)
  Real r;                ///< r = M'/S
};

GreenhallSetup greenhall_setup(const char* where, int alpha, int d, std::int64_t m,
                               std::int64_t n_phase, bool overlapping, bool modified) {
  const std::string w(where);
  IMUNOISE_EXPECT(d >= 1 && d <= 3, w + ": d must be 1, 2 or 3 (got " + std::to_string(d) + ")");
  IMUNOISE_CHECK(alpha >= -4 && alpha <= 2, AnalysisError,
                 w + ": alpha must be in -4..2 (got " + std::to_string(alpha) + ")");
  IMUNOISE_CHECK(alpha + 2 * d > 1, AnalysisError,
                 w + ": alpha + 2d must exceed 1, the variance diverges otherwise (alpha=" +
                     std::to_string(alpha) + ", d=" + std::to_string(d) + ")");
  IMUNOISE_EXPECT(m >= 1, w + ": m must be >= 1 (got " + std::to_string(m) + ")");
  const std::int64_t f = modified ? 1 : m;
  const std::int64_t s = overlapping ? m : 1;
  const std::int64_t l = m / f + m * d;  // span of the filter in phase samples
  IMUNOISE_CHECK(n_phase >= l, AnalysisError,
                 w + ": too few phase samples (M=" + std::to_string(n_phase) +
                     ", need >= " + std::to_string(l) + " for m=" + std::to_string(m) + ")");
  GreenhallSetup g{};
  g.f = static_cast<Real>(f);
  g.s = static_cast<Real>(s);
  // S ∈ {1, m}: S(M − L)/m is M − L exactly when overlapping, so the product S·(M − L) — which
  // exceeds 2^63 for M ≳ 6·10^9 at the largest m — is never formed. Non-negative operands:
  // integer division = floor.
  g.m_terms = 1 + (overlapping ? n_phase - l : (n_phase - l) / m);
  g.j = std::min(g.m_terms, (d + 1) * s);
  g.r = static_cast<Real>(g.m_terms) / g.s;
  return g;
}

/// Coefficient table lookup; zeros mark (alpha, d) pairs outside alpha + 2d > 1.
GreenhallCoefficients table_entry(const std::array<std::array<double, 6>, 7>& table, int alpha,
                                  int d, const char* name) {
  IMUNOISE_CHECK(d >= 1 && d <= 3 && alpha >= -4 && alpha <= 2 && alpha + 2 * d > 1, AnalysisError,
                 std::string(name) + ": no entry for alpha=" + std::to_string(alpha) +
                     ", d=" + std::to_string(d));
  const auto& row = table[static_cast<std::size_t>(2 - alpha)];
  const auto col = static_cast<std::size_t>(2 * (d - 1));
  return {row[col], row[col + 1]};
}

}  // namespace

GreenhallCoefficients greenhall_table1(int alpha, int d) {
  // GR03 Table 1, modified variances; columns (a0, a1) for d = 1, 2, 3; rows alpha 2 … −4.
  // Cross-checked in tests against edf_greenhall_direct() at large m.
  static constexpr std::array<std::array<double, 6>, 7> kTable1 = {{
      {2.0 / 3.0, 1.0 / 3.0, 7.0 / 9.0, 1.0 / 2.0, 22.0 / 25.0, 2.0 / 3.0},
      {0.840, 0.345, 0.997, 0.616, 1.141, 0.843},
      {1.079, 0.368, 1.033, 0.607, 1.184, 0.848},
      {0.0, 0.0, 1.048, 0.534, 1.180, 0.816},
      {0.0, 0.0, 1.302, 0.535, 1.175, 0.777},
      {0.0, 0.0, 0.0, 0.0, 1.194, 0.703},
      {0.0, 0.0, 0.0, 0.0, 1.489, 0.702},
  }};
  return table_entry(kTable1, alpha, d, "greenhall_table1");
}

GreenhallCoefficients greenhall_table2(int alpha, int d) {
  // GR03 Table 2, unmodified variances (F → ∞); the alpha = 2 row is exact:
  // a0 = C(4d,2d)/C(2d,d)², a1 = d/2.
  static constexpr std::array<std::array<double, 6>, 7> kTable2 = {{
      {3.0 / 2.0, 1.0 / 2.0, 35.0 / 18.0, 1.0, 231.0 / 100.0, 3.0 / 2.0},
      {78.6, 25.2, 790.0, 410.0, 9950.0, 6520.0},
      {2.0 / 3.0, 1.0 / 6.0, 2.0 / 3.0, 1.0 / 3.0, 7.0 / 9.0, 1.0 / 2.0},
      {0.0, 0.0, 0.852, 0.375, 0.997, 0.617},
      {0.0, 0.0, 1.079, 0.368, 1.033, 0.607},
      {0.0, 0.0, 0.0, 0.0, 1.053, 0.553},
      {0.0, 0.0, 0.0, 0.0, 1.302, 0.535},
  }};
  return table_entry(kTable2, alpha, d, "greenhall_table2");
}

GreenhallCoefficients greenhall_table3(int d) {
  // GR03 Table 3: s_z(0; F=m, alpha=1, d) ≈ b0 + b1·ln m for large m.
  static constexpr std::array<GreenhallCoefficients, 3> kTable3 = {
      {{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}}};
  IMUNOISE_EXPECT(d >= 1 && d <= 3,
                  "greenhall_table3: d must be 1, 2 or 3 (got " + std::to_string(d) + ")");
  return kTable3[static_cast<std::size_t>(d - 1)];
}

double edf_greenhall(int alpha, int d, std::int64_t m, std::int64_t n_phase, bool overlapping,
                     bool modified) {
  const GreenhallSetup g =
      greenhall_setup("edf_greenhall", alpha, d, m, n_phase, overlapping, modified);
  const Real m_terms = static_cast<Real>(g.m_terms);
  const Real jmax = static_cast<Real>(kJmax);
  const bool table_regime = g.j > kJmax && g.r >= d + 1;
  Real inv_edf = 0;

  if (g.f == 1) {
    // Case 1: modified variances, all alpha. Stable32 also routes unmodified variances at
    // m = 1 (F = m = 1) here; for J ≤ Jmax that is the same sum as cases 2–4.
    const Real z0 = s_z(0, 1, alpha, d);
    if (g.j <= kJmax) {
      inv_edf = basic_sum(g.j, m_terms, g.s, 1, alpha, d) / (z0 * z0 * m_terms);
    } else if (table_regime) {
      const auto [a0, a1] = greenhall_table1(alpha, d);
      inv_edf = (a0 - a1 / g.r) / g.r;
    } else {
      // r < d+1: keep the shape of the sum with Jmax terms and stride m' = Jmax/r.
      inv_edf = basic_sum(kJmax, jmax, jmax / g.r, 1, alpha, d) / (z0 * z0 * jmax);
    }
  } else if (alpha <= 0) {
    // Case 2: unmodified, white FM and below. F = m is replaced by its limit F = ∞ as soon
    // as the filter spans more than Jmax samples, m(d+1) > Jmax.
    if (g.j <= kJmax) {
      const Real f = (g.f * (d + 1) <= jmax) ? g.f : kInfiniteF;
      const Real z0 = s_z(0, f, alpha, d);
      inv_edf = basic_sum(g.j, m_terms, g.s, f, alpha, d) / (z0 * z0 * m_terms);
    } else if (table_regime) {
      const auto [a0, a1] = greenhall_table2(alpha, d);
      inv_edf = (a0 - a1 / g.r) / g.r;
    } else {
      const Real z0 = s_z(0, kInfiniteF, alpha, d);
      inv_edf = basic_sum(kJmax, jmax, jmax / g.r, kInfiniteF, alpha, d) / (z0 * z0 * jmax);
    }
  } else if (alpha == 1) {
    // Case 3: unmodified flicker PM; s_z grows like ln m, so F = m is kept (long double
    // keeps the F² cancellation harmless far beyond GR03's "m < 1e6" limit for double).
    if (g.j <= kJmax) {
      const Real z0 = s_z(0, g.f, 1, d);
      inv_edf = basic_sum(g.j, m_terms, g.s, g.f, 1, d) / (z0 * z0 * m_terms);
    } else {
      const auto [b0, b1] = greenhall_table3(d);
      const Real z0 = b0 + b1 * std::log(static_cast<Real>(m));
      if (table_regime) {
        const auto [a0, a1] = greenhall_table2(1, d);
        inv_edf = (a0 - a1 / g.r) / (z0 * z0 * g.r);
      } else {
        const Real mp = jmax / g.r;
        inv_edf = basic_sum(kJmax, jmax, mp, mp, 1, d) / (z0 * z0 * jmax);
      }
    }
  } else {
    // Case 4: unmodified white PM. The d-th differences of white phase are correlated only
    // at lags that are whole multiples of τ, with s_z(k) ∝ (−1)^k C(2d, d+k), so the sum is
    // exact in closed form: K = ⌈r⌉; K > d gives 1/ν = (a0 − a1/r)/M' (Table 2, alpha=2).
    const auto k_ceil = static_cast<std::int64_t>(std::ceil(g.r));
    if (k_ceil <= d) {
      const double c0 = binomial(2 * d, d);
      Real sum = 0;
      for (std::int64_t k = 1; k < k_ceil; ++k) {
        const double ck = binomial(2 * d, d - static_cast<int>(k));
        sum += (1 - static_cast<Real>(k) / g.r) * ck * ck;
      }
      inv_edf = (1 + 2 * sum / (c0 * c0)) / m_terms;
    } else {
      const auto [a0, a1] = greenhall_table2(2, d);
      inv_edf = (a0 - a1 / g.r) / m_terms;
    }
  }
  return static_cast<double>(1 / inv_edf);
}

double edf_greenhall_direct(int alpha, int d, std::int64_t m, std::int64_t n_phase,
                            bool overlapping, bool modified) {
  const GreenhallSetup g =
      greenhall_setup("edf_greenhall_direct", alpha, d, m, n_phase, overlapping, modified);
  const Real m_terms = static_cast<Real>(g.m_terms);
  const Real z0 = s_z(0, g.f, alpha, d);
  return static_cast<double>(z0 * z0 * m_terms / basic_sum(g.j, m_terms, g.s, g.f, alpha, d));
}

double edf_totdev(int alpha, std::int64_t m, std::int64_t n_phase) {
  IMUNOISE_CHECK(m >= 1 && n_phase >= 2 * m, AnalysisError,
                 "edf_totdev: need m >= 1 and M >= 2m (T/tau >= 2), got m=" + std::to_string(m) +
                     ", M=" + std::to_string(n_phase));
  IMUNOISE_CHECK(alpha >= -2 && alpha <= 2, AnalysisError,
                 "edf_totdev: alpha must be in -2..2 (got " + std::to_string(alpha) + ")");
  // PM noise: SP1065 Table 7 has no entry. Stable32 then prints the SP1065 Table 5 simple
  // EDF with M phase samples (implied ν of its TOTDEV tables: OCXO m=8 alpha=1 ≈ 8170 vs
  // 8067·1.013 simple, Keysight m=2048 ≈ 936 vs 923·1.013; the GR03 OADEV EDF gives 5610
  // and 371 — the 1.3 % is Stable32's χ² quirk above ν = 100, see the Stable32 test).
  // TOTDEV ≈ OADEV for PM noise, so the OADEV formula is also the natural model.
  if (alpha > 0) return edf_simple_oadev(alpha, m, n_phase);
  // SP1065 Table 7 (Howe & Greenhall 1997); T = M·τ0, so T/τ = M/m.
  static constexpr std::array<std::array<double, 2>, 3> kTable7 = {
      {{1.50, 0.0}, {1.17, 0.22}, {0.93, 0.36}}};
  const auto& [b, c] = kTable7[static_cast<std::size_t>(-alpha)];
  return b * static_cast<double>(n_phase) / static_cast<double>(m) - c;
}

double edf_simple_oadev(int alpha, std::int64_t m, std::int64_t n_phase) {
  IMUNOISE_CHECK(m >= 1 && n_phase > 2 * m && n_phase > 3, AnalysisError,
                 "edf_simple_oadev: need m >= 1 and M > 2m (got m=" + std::to_string(m) +
                     ", M=" + std::to_string(n_phase) + ")");
  const double n = static_cast<double>(n_phase);
  const double mm = static_cast<double>(m);
  switch (alpha) {
    case 2:
      return (n + 1.0) * (n - 2.0 * mm) / (2.0 * (n - mm));
    case 1:
      return std::exp(std::sqrt(std::log((n - 1.0) / (2.0 * mm)) *
                                std::log((2.0 * mm + 1.0) * (n - 1.0) / 4.0)));
    case 0:
      return (3.0 * (n - 1.0) / (2.0 * mm) - 2.0 * (n - 2.0) / n) * 4.0 * mm * mm /
             (4.0 * mm * mm + 5.0);
    case -1:
      // m = 1: the squared form; allantools and its copies drop the square (theory.md §9.1).
      if (m == 1) return 2.0 * (n - 2.0) * (n - 2.0) / (2.3 * n - 4.9);
      return 5.0 * n * n / (4.0 * mm * (n + 3.0 * mm));
    case -2:
      return (n - 2.0) / mm * ((n - 1.0) * (n - 1.0) - 3.0 * mm * (n - 1.0) + 4.0 * mm * mm) /
             ((n - 3.0) * (n - 3.0));
    default:
      throw AnalysisError("edf_simple_oadev: alpha must be in -2..2 (got " + std::to_string(alpha) +
                          ")");
  }
}

}  // namespace imunoise::analysis
