/// @file
/// @brief How precisely the OAVAR points of a record can determine N, B and K: the spread of
/// the best linear unbiased estimate from them (generalized least squares with the exact
/// covariance of the estimates, the Gauss–Markov bound (ΦᵀC⁻¹Φ)⁻¹ for the squared coefficients)
/// and of the default estimator's linearization (independent-point weights W = ν/(2m²), spread
/// (ΦᵀWΦ)⁻¹ΦᵀWCWΦ(ΦᵀWΦ)⁻¹), each as the expected median |relative error| 0.674·sd(c²)/(2c²) of a
/// Gaussian estimate, for the truth's structure known (no model selection). Covariance, EDF and
/// points from analysis/variance_covariance.h at the log:10 grid the analysis uses, τ with
/// EDF < 4 left out as the fit does. A study of what the record's OAVAR carries, for stating the
/// conditions of issue 20's error targets (B ≤ 5 %, K ≤ 15 %); the estimator's measured errors
/// are the battery's (docs/validation.md).
///
///   precision_bound
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <vector>

#include "analysis/deviation_type.h"
#include "analysis/noise_terms.h"
#include "analysis/tau_grid.h"
#include "analysis/variance_covariance.h"

namespace {

using namespace imunoise;
using namespace imunoise::analysis;

constexpr double kPi = 3.14159265358979323846;

struct Case {
  const char* name;
  NoiseCoefficients truth;
  double rate_hz;
  double hours;
};

NoiseCoefficients coefficients(double q, double n, double b, double k, double r) {
  NoiseCoefficients c;
  c.quantization = q;
  c.white_noise = n;
  c.bias_instability = b;
  c.random_walk = k;
  c.ramp = r;
  return c;
}

}  // namespace

int main() {
  // The battery's grade channels (docs/validation.md "Grades"; x axes, and the accel y of the
  // tactical grade), at their own rates and lengths and at other lengths.
  const NoiseCoefficients consumer_gyro = coefficients(0, 1.745e-4, 4.848e-5, 4.040e-6, 0);
  const NoiseCoefficients consumer_accel = coefficients(0, 1.471e-3, 3.923e-4, 3.923e-5, 0);
  const NoiseCoefficients industrial_gyro = coefficients(0, 4.363e-5, 9.696e-6, 4.040e-7, 0);
  const NoiseCoefficients industrial_accel = coefficients(0, 3.333e-4, 4.903e-5, 1.961e-6, 0);
  const NoiseCoefficients tactical_gyro = coefficients(2e-6, 1.454e-5, 1.454e-6, 4.040e-8, 0);
  const NoiseCoefficients tactical_accel = coefficients(0, 6e-4, 2.354e-4, 5.884e-6, 0);
  std::vector<Case> cases;
  for (double hours : {1.0, 4.0, 12.0}) {
    cases.push_back({"consumer gyro_x", consumer_gyro, 1000.0, hours});
    cases.push_back({"consumer accel_x", consumer_accel, 1000.0, hours});
  }
  for (double hours : {2.0, 4.0, 12.0}) {
    cases.push_back({"industrial gyro_x", industrial_gyro, 400.0, hours});
    cases.push_back({"industrial accel_x", industrial_accel, 400.0, hours});
  }
  for (double hours : {2.0, 4.0, 12.0, 24.0}) {
    cases.push_back({"industrial gyro_x", industrial_gyro, 100.0, hours});
    cases.push_back({"industrial accel_x", industrial_accel, 100.0, hours});
  }
  for (double hours : {2.0, 12.0}) {
    cases.push_back({"tactical gyro_x", tactical_gyro, 100.0, hours});
    cases.push_back({"tactical accel_y", tactical_accel, 100.0, hours});
  }
  std::printf(
      "| channel | rate [Hz] | length [h] | points | N: GLS bound / default | B: GLS bound "
      "/ default | K: GLS bound / default | B: Whittle | K: Whittle |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    const double tau0 = 1.0 / c.rate_hz;
    const auto n = static_cast<std::int64_t>(c.hours * 3600.0 * c.rate_hz);
    const std::vector<std::int64_t> all_m =
        averaging_factors(parse_tau_grid("log:10"), DeviationType::oadev, n + 1);
    const VarianceCovariance all = overlapping_variance_covariance(c.truth, tau0, n, all_m);
    std::vector<std::int64_t> m;
    for (std::size_t i = 0; i < all_m.size(); ++i)
      if (all.edf[i] >= 4.0) m.push_back(all_m[i]);
    const VarianceCovariance vc = overlapping_variance_covariance(c.truth, tau0, n, m);
    std::vector<NoiseTerm> terms;
    for (NoiseTerm t : kNoiseTerms)
      if (coefficient(c.truth, t) > 0.0) terms.push_back(t);
    const auto k = static_cast<Eigen::Index>(m.size());
    const auto p = static_cast<Eigen::Index>(terms.size());
    Eigen::MatrixXd phi(k, p);
    Eigen::VectorXd w(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const double tau = static_cast<double>(m[static_cast<std::size_t>(i)]) * tau0;
      for (Eigen::Index j = 0; j < p; ++j)
        phi(i, j) = term_avar_basis(terms[static_cast<std::size_t>(j)], tau);
      const double e = vc.expected[static_cast<std::size_t>(i)];
      w(i) = vc.edf[static_cast<std::size_t>(i)] / (2.0 * e * e);
    }
    const Eigen::MatrixXd& cov = vc.covariance;
    const Eigen::MatrixXd gls = (phi.transpose() * cov.ldlt().solve(phi)).inverse();
    const Eigen::MatrixXd bread = (phi.transpose() * w.asDiagonal() * phi).inverse();
    const Eigen::MatrixXd wls =
        bread * (phi.transpose() * w.asDiagonal() * cov * w.asDiagonal() * phi) * bread;
    // The Whittle (periodogram) Fisher information of the same coefficients from the whole
    // record: each Fourier ordinate f_k = k/T, 0 < k < n/2, is S(f_k)·Exp(1) with S the
    // two-sided density (theory.md §5.3: Q 4sin²(πfτ0)Q²/τ0, N N², B B²/(2πf), K K²/(2πf)²), so
    // I = Σ_k ∇S ∇Sᵀ / S² — the asymptotic information of the Gaussian likelihood, what any
    // estimator from the samples (not only from the OAVAR points) can reach.
    Eigen::MatrixXd fisher = Eigen::MatrixXd::Zero(p, p);
    {
      const double record = static_cast<double>(n) * tau0;
      Eigen::VectorXd g(p);
      for (std::int64_t q = 1; 2 * q < n; ++q) {
        const double f = static_cast<double>(q) / record;
        const double w = 2.0 * kPi * f;
        double density = 0.0;
        for (Eigen::Index j = 0; j < p; ++j) {
          const NoiseTerm t = terms[static_cast<std::size_t>(j)];
          const double sine = std::sin(kPi * f * tau0);
          g(j) = t == NoiseTerm::quantization       ? 4.0 * sine * sine / tau0
                 : t == NoiseTerm::white_noise      ? 1.0
                 : t == NoiseTerm::bias_instability ? 1.0 / w
                 : t == NoiseTerm::random_walk      ? 1.0 / (w * w)
                                                    : 0.0;
          density += g(j) * std::pow(coefficient(c.truth, t), 2);
        }
        fisher.noalias() += g * g.transpose() / (density * density);
      }
    }
    const Eigen::MatrixXd whittle = fisher.inverse();
    std::printf("| %s | %.0f | %.0f | %lld |", c.name, c.rate_hz, c.hours,
                static_cast<long long>(k));
    // Median |x| of a normal of sd s is 0.674·s; d(c²)/c² = 2 dc/c. "—" for a term the truth
    // lacks.
    const auto print_median_errors = [&](NoiseTerm t,
                                         std::initializer_list<const Eigen::MatrixXd*> spreads,
                                         const char* separator) {
      const auto it = std::find(terms.begin(), terms.end(), t);
      if (it == terms.end()) {
        std::printf(" — |");
        return;
      }
      const auto j = static_cast<Eigen::Index>(it - terms.begin());
      const double c2 = std::pow(coefficient(c.truth, t), 2);
      const char* sep = " ";
      for (const Eigen::MatrixXd* v : spreads) {
        std::printf("%s%.2f %%", sep,
                    100.0 * 0.674 * std::sqrt(std::max((*v)(j, j), 0.0)) / (2.0 * c2));
        sep = separator;
      }
      std::printf(" |");
    };
    for (NoiseTerm t :
         {NoiseTerm::white_noise, NoiseTerm::bias_instability, NoiseTerm::random_walk})
      print_median_errors(t, {&gls, &wls}, " / ");
    for (NoiseTerm t : {NoiseTerm::bias_instability, NoiseTerm::random_walk})
      print_median_errors(t, {&whittle}, "");
    std::printf("\n");
  }
  return 0;
}
