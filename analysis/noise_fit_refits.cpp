/// @file
/// @brief The refits of a given structure (the interval draws' and GLS's), the least-squares
/// intervals, the profile upper bounds and the fit with a term held (see noise_fit.h; theory.md
/// §4.3).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/chi_square.h"
#include "analysis/noise_fit.h"
#include "analysis/noise_fit_internal.h"
#include "analysis/noise_terms.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"

namespace imunoise::analysis {

namespace fit_detail {

/// The points FIT used (POINTS[USED]) as fit data; WHERE names the caller in errors.
Data used_data(std::span<const FitPoint> points, std::span<const std::size_t> used,
               const char* where) {
  Data data;
  for (std::size_t k : used) {
    IMUNOISE_EXPECT(k < points.size(), std::string(where) + ": used index " + std::to_string(k) +
                                           " is out of range (" + std::to_string(points.size()) +
                                           " points)");
    const FitPoint& p = points[k];
    IMUNOISE_CHECK(p.avar > 0.0 && p.edf > 0.0, AnalysisError,
                   std::string(where) + ": point " + std::to_string(k) +
                       " has a zero variance or no EDF and cannot be fitted");
    data.tau.push_back(p.tau_s);
    data.y.push_back(p.avar);
    data.nu.push_back(p.edf);
    data.index.push_back(k);
  }
  return data;
}

/// The columns of a fitted structure: its identified power-law terms, its sinusoid
/// frequencies and its GM correlation times.
std::vector<Column> structure_columns(const FitResult& structure) {
  std::vector<Column> columns;
  for (NoiseTerm term : kNoiseTerms)
    if (structure.terms[term].identified)
      columns.push_back({ColumnKind::power_law, term, 0.0, 0.0});
  for (const Sinusoid& sine : structure.coefficients.sinusoids)
    columns.push_back({ColumnKind::sinusoid, NoiseTerm::white_noise, 0.0, sine.frequency_hz});
  for (const GaussMarkov& gm : structure.coefficients.gauss_markov)
    columns.push_back({ColumnKind::gauss_markov, NoiseTerm::white_noise, gm.tau_c_s, 0.0});
  return columns;
}

}  // namespace fit_detail

using namespace fit_detail;

namespace {

FitResult refit_structure(std::span<const FitPoint> points, const FitResult& structure,
                          const FitOptions& options, std::span<const double> used_correlation,
                          bool full_result, const char* where) {
  validate_options(options);
  validate_points(points, where);
  IMUNOISE_EXPECT(structure.used.size() >= 2,
                  std::string(where) + ": the structure uses fewer than 2 points");
  Data data = used_data(points, structure.used, where);
  if (!used_correlation.empty()) {
    const auto n = static_cast<Eigen::Index>(data.size());
    IMUNOISE_EXPECT(used_correlation.size() == data.size() * data.size(),
                    std::string(where) + ": the correlation matrix has " +
                        std::to_string(used_correlation.size()) + " entries for " +
                        std::to_string(data.size()) + " used points");
    data.correlation_factor = correlation_factor(
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            used_correlation.data(), n, n));
    data.weight_model.resize(static_cast<Eigen::Index>(data.size()));
    for (std::size_t k = 0; k < data.size(); ++k)
      data.weight_model(static_cast<Eigen::Index>(k)) =
          model_variance(structure.coefficients, data.tau[k], structure.hadamard);
  }
  const bool hadamard = structure.hadamard;
  std::vector<Column> columns = structure_columns(structure);
  IMUNOISE_CHECK(!columns.empty(), AnalysisError,
                 std::string(where) + ": the structure has no identified term");
  refine_gauss_markov(data, columns, hadamard, options.weight_iterations,
                      brackets_around(columns, kRefitBracket));
  const Solution s = solve(data, columns, hadamard, options.weight_iterations, zero_offset(data));
  return make_result(points, data, columns, s, hadamard, effective_point_count(data),
                     full_result ? structure.selection_note : "", full_result);
}

}  // namespace

FitResult refit_fixed_terms(std::span<const FitPoint> points, const FitResult& structure,
                            const FitOptions& options, std::span<const double> used_correlation) {
  return refit_structure(points, structure, options, used_correlation, false, "refit_fixed_terms");
}

FitResult generalized_refit(std::span<const FitPoint> points, const FitResult& fit,
                            const FitOptions& options, std::span<const double> used_correlation) {
  IMUNOISE_EXPECT(!used_correlation.empty(), "generalized_refit: no correlation matrix");
  return refit_structure(points, fit, options, used_correlation, true, "generalized_refit");
}

PerTerm<CoefficientInterval> least_squares_intervals(std::span<const FitPoint> points,
                                                     const FitResult& fit, double confidence) {
  PerTerm<CoefficientInterval> out{};
  std::vector<NoiseTerm> active;
  for (NoiseTerm term : kNoiseTerms) {
    const TermFit& t = fit.terms[term];
    if (t.identified && t.value > 0.0) active.push_back(term);
  }
  if (active.empty() || fit.used.empty()) return out;
  const Data data = used_data(points, fit.used, "least_squares_intervals");
  const auto p = static_cast<Eigen::Index>(active.size());
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(p, p);
  for (std::size_t k = 0; k < data.size(); ++k) {
    const double model = model_variance(fit.coefficients, data.tau[k], fit.hadamard);
    if (!(model > 0.0)) continue;
    Eigen::VectorXd phi(p);
    for (Eigen::Index i = 0; i < p; ++i) {
      phi(i) = term_basis(active[static_cast<std::size_t>(i)], data.tau[k], fit.hadamard);
    }
    normal += data.nu[k] / (2.0 * model * model) * phi * phi.transpose();
  }
  const Eigen::MatrixXd cov = normal.completeOrthogonalDecomposition().pseudoInverse();
  // Two-sided normal quantile: P(Z² ≤ z²) = confidence with Z² ~ χ²₁.
  const double z = std::sqrt(chi_square_quantile(confidence, 1.0));
  for (Eigen::Index i = 0; i < p; ++i) {
    const auto t = static_cast<std::size_t>(active[static_cast<std::size_t>(i)]);
    const double c = fit.terms[t].value;
    const double sd_c = std::sqrt(std::max(cov(i, i), 0.0)) / (2.0 * c);  // d(c²) = 2c·dc
    out[t] = {std::max(0.0, c - z * sd_c), c + z * sd_c};
  }
  return out;
}

namespace {

/// f = uᵀCu/uᵀu (at least 1) for the weighted basis PHI of a term, u made orthogonal to the
/// columns the fit without it uses (coefficient > 0), with the weights √(ν/2)/m of its
/// solution: the factor by which the correlation C of the estimates inflates the variance of
/// the term's estimate over the independent-points value the deviance assumes.
double direction_inflation(const Data& data, const std::vector<Column>& columns, bool hadamard,
                           int weight_iterations, const Eigen::VectorXd& phi,
                           std::span<const double> correlation, double c_at) {
  const auto n = static_cast<Eigen::Index>(data.size());
  const Solution s = solve(data, columns, hadamard, weight_iterations, c_at * c_at * phi);
  Eigen::VectorXd scale(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    scale(k) = std::sqrt(0.5 * data.nu[i]) / floored(s.model(k), data.y[i]);
  }
  std::vector<Eigen::Index> active;
  for (Eigen::Index j = 0; j < s.c.size(); ++j)
    if (s.c(j) > 0.0) active.push_back(j);
  Eigen::MatrixXd a(n, static_cast<Eigen::Index>(active.size()));
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index k = 0; k < n; ++k)
      a(k, j) =
          scale(k) * basis(columns[static_cast<std::size_t>(active[static_cast<std::size_t>(j)])],
                           data.tau[static_cast<std::size_t>(k)], hadamard);
  Eigen::VectorXd u = scale.cwiseProduct(phi);
  if (a.cols() > 0) u -= a * a.colPivHouseholderQr().solve(u);
  const double uu = u.squaredNorm();
  if (!(uu > 0.0)) return 1.0;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> c(
      correlation.data(), n, n);
  const double f = u.dot(c * u) / uu;
  return std::isfinite(f) ? std::max(f, 1.0) : 1.0;
}

/// How profile_bound() measures and searches. The power-law bounds set only d_ref (D without the
/// term; the rest as when they were validated); the Gauss–Markov curve sets all four.
struct ProfileRule {
  double c_start = 0.0;  ///< where the search starts: the best c (the profile's optimum)
  double d_ref = 0.0;    ///< the deviance the rise is measured from
  /// χ²_p with p = 1 + the number of COLUMNS the held fit sets to zero, instead of χ²₁: a term
  /// pushed onto its bound c ≥ 0 makes the profile statistic a chi-bar-square mixture of up to
  /// that many more degrees of freedom (a random walk that stands in for a Gauss–Markov term
  /// goes to 0 when the GM is held near its truth; measured in
  /// tests/analysis/gauss_markov_bound_test.cpp: with χ²₁ the bound held the truth in 88 % of
  /// the draws, the statistic's quantiles ~1.55× those of χ²₁, i.e. close to χ²₂).
  bool chi_bar = false;
  /// Bisection in ln c from 1e-8 of the bracket's top, 26 halvings (3e-7 relative), instead of
  /// 60 linear halvings: under half the solves, for the ~20 bounds per axis of the GM curve.
  bool log_search = false;
};

/// The coefficient c ≥ RULE.c_start at which c²·PHI held in the model (COLUMNS re-fitted by the
/// re-weighted NNLS) raises the deviance over RULE.d_ref by χ²(CONFIDENCE)·f (χ²₁, or χ²_p with
/// RULE.chi_bar), f the variance inflation of PHI's direction under USED_CORRELATION at c_start
/// (n_used/n_eff without it); infinity if no c within reach of the data (c²·PHI 100× the data at
/// its most favourable point) does.
double profile_bound(const Data& data, const std::vector<Column>& columns, bool hadamard,
                     const Eigen::VectorXd& phi, double confidence, int weight_iterations,
                     std::span<const double> used_correlation, const ProfileRule& rule,
                     const char* where) {
  const auto n = static_cast<Eigen::Index>(data.size());
  double inflation = static_cast<double>(data.size()) / effective_point_count(data);
  if (!used_correlation.empty()) {
    IMUNOISE_EXPECT(used_correlation.size() == data.size() * data.size(),
                    std::string(where) + ": the correlation must be n_used x n_used");
    inflation = direction_inflation(data, columns, hadamard, weight_iterations, phi,
                                    used_correlation, rule.c_start);
  }
  const double target_one = chi_square_quantile(confidence, 1.0) * inflation;
  // Whether c is beyond the bound: the deviance of the best fit of the other terms with c²·φ
  // held in the model, over D_REF, above the target.
  const auto beyond = [&](double c) {
    const Solution s = solve(data, columns, hadamard, weight_iterations, c * c * phi);
    double target = target_one;
    if (rule.chi_bar) {
      const auto zero = static_cast<double>((s.c.array() <= 0.0).count());
      if (zero > 0.0) target = chi_square_quantile(confidence, 1.0 + zero) * inflation;
    }
    return s.deviance - rule.d_ref > target;
  };
  double c_hi = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (phi(k) > 0.0) {
      c_hi = std::max(c_hi, std::sqrt(100.0 * data.y[static_cast<std::size_t>(k)] / phi(k)));
    }
  }
  if (!(c_hi > rule.c_start) || !beyond(c_hi)) return std::numeric_limits<double>::infinity();
  double c_lo = rule.c_start;
  if (rule.log_search) {
    c_lo = std::max(c_lo, 1e-8 * c_hi);
    if (beyond(c_lo)) return c_lo;
    for (int i = 0; i < 26; ++i) {
      const double mid = std::sqrt(c_lo * c_hi);
      (beyond(mid) ? c_hi : c_lo) = mid;
    }
    return c_hi;
  }
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (c_lo + c_hi);
    (beyond(mid) ? c_hi : c_lo) = mid;
  }
  return c_hi;
}

}  // namespace

double profile_upper_bound(std::span<const FitPoint> points, const FitResult& fit, NoiseTerm term,
                           double confidence, int weight_iterations,
                           std::span<const double> used_correlation) {
  if (fit.used.empty()) return std::numeric_limits<double>::infinity();
  const Data data = used_data(points, fit.used, "profile_upper_bound");
  std::vector<Column> columns = structure_columns(fit);
  std::erase_if(columns, [term](const Column& c) {
    return c.kind == ColumnKind::power_law && c.term == term;
  });
  const auto n = static_cast<Eigen::Index>(data.size());
  Eigen::VectorXd phi(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    phi(k) = term_basis(term, data.tau[static_cast<std::size_t>(k)], fit.hadamard);
  }
  // The reference is the deviance without the term (the selection dropped it, so the minimum
  // over c is at or near 0; starting from D(0) keeps the bound on the safe side).
  const double d0 =
      solve(data, columns, fit.hadamard, weight_iterations, zero_offset(data)).deviance;
  return profile_bound(data, columns, fit.hadamard, phi, confidence, weight_iterations,
                       used_correlation, ProfileRule{.d_ref = d0}, "profile_upper_bound");
}

std::vector<double> gauss_markov_bound_grid(double tau_min_s, double tau_max_s, int per_decade) {
  IMUNOISE_EXPECT(
      tau_min_s > 0.0 && tau_min_s <= tau_max_s && std::isfinite(tau_max_s) && per_decade >= 1,
      "gauss_markov_bound_grid: needs 0 < tau_min <= tau_max and per_decade >= 1");
  const double step = static_cast<double>(per_decade);
  // A small tolerance so that a τ on a grid value (10 s) does not add the next one below.
  const auto first = static_cast<int>(std::floor(std::log10(tau_min_s) * step + 1e-9));
  const auto last = static_cast<int>(std::ceil(std::log10(tau_max_s) * step - 1e-9));
  std::vector<double> grid;
  for (int j = first; j <= last; ++j) {
    // Three significant digits (1, 1.78, 3.16, 5.62, 10 …), divided by an exact power of ten so
    // that the value is the double nearest the decimal and model.yaml shows it as such.
    const double v = std::pow(10.0, j / step);
    const int e = 2 - static_cast<int>(std::floor(std::log10(v) + 1e-9));
    const double p = std::pow(10.0, std::abs(e));  // exact up to 1e22
    grid.push_back(e >= 0 ? std::round(v * p) / p : std::round(v / p) * p);
  }
  return grid;
}

std::vector<GaussMarkovBound> gauss_markov_upper_bounds(std::span<const FitPoint> points,
                                                        const FitResult& fit,
                                                        std::span<const double> tau_c_grid_s,
                                                        double confidence, int weight_iterations,
                                                        std::span<const double> used_correlation) {
  std::vector<GaussMarkovBound> bounds;
  if (fit.used.size() < 2) return bounds;
  const Data data = used_data(points, fit.used, "gauss_markov_upper_bounds");
  const std::vector<Column> columns = structure_columns(fit);
  const auto n = static_cast<Eigen::Index>(data.size());
  // The reference is the reported model (no further GM), as for the power-law bounds: a GM that
  // fits no worse than it, within the test's threshold, is not excluded. Where the data favour
  // a GM the selection did not keep, the profile dips below D(0) and the bound moves out.
  const double d0 =
      solve(data, columns, fit.hadamard, weight_iterations, zero_offset(data)).deviance;
  // The structure and one more GM column, whose T_c each grid point sets.
  std::vector<Column> with_gm = columns;
  with_gm.push_back({ColumnKind::gauss_markov, NoiseTerm::white_noise, 0.0, 0.0});
  for (double tau_c : tau_c_grid_s) {
    IMUNOISE_EXPECT(tau_c > 0.0 && std::isfinite(tau_c),
                    "gauss_markov_upper_bounds: a correlation time must be positive");
    Column& gm = with_gm.back();
    gm.tau_c_s = tau_c;
    Eigen::VectorXd phi(n);
    for (Eigen::Index k = 0; k < n; ++k)
      phi(k) = basis(gm, data.tau[static_cast<std::size_t>(k)], fit.hadamard);
    // The GM free (one more NNLS column): its best σ, where the search starts and the
    // correlation's inflation of its direction is taken (the profile's optimum).
    const Solution best = solve(data, with_gm, fit.hadamard, weight_iterations, zero_offset(data));
    const double sigma_best = std::sqrt(std::max(best.c(best.c.size() - 1), 0.0));
    const double sigma_max = profile_bound(
        data, columns, fit.hadamard, phi, confidence, weight_iterations, used_correlation,
        ProfileRule{.c_start = sigma_best, .d_ref = d0, .chi_bar = true, .log_search = true},
        "gauss_markov_upper_bounds");
    if (std::isfinite(sigma_max)) bounds.push_back({tau_c, sigma_max});
  }
  return bounds;
}

FitResult refit_with_term_held(std::span<const FitPoint> points, const FitResult& fit,
                               NoiseTerm term, double held, int weight_iterations) {
  IMUNOISE_EXPECT(
      !fit.terms[term].identified && std::isfinite(held) && held >= 0.0 && fit.used.size() >= 2,
      "refit_with_term_held: needs a dropped term, a finite value >= 0 and 2 used points");
  const Data data = used_data(points, fit.used, "refit_with_term_held");
  const std::vector<Column> columns = structure_columns(fit);
  Eigen::VectorXd offset(static_cast<Eigen::Index>(data.size()));
  for (std::size_t k = 0; k < data.size(); ++k)
    offset(static_cast<Eigen::Index>(k)) =
        held * held * term_basis(term, data.tau[k], fit.hadamard);
  const Solution s = solve(data, columns, fit.hadamard, weight_iterations, offset);
  FitResult r = make_result(points, data, columns, s, fit.hadamard, fit.effective_points, "",
                            /*residuals=*/false);
  coefficient(r.coefficients, term) = held;
  return r;
}

}  // namespace imunoise::analysis
