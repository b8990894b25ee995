/// @file
/// @brief How often the noise fit identifies a term, on OAVAR vectors drawn from their joint
/// distribution under a known model (analysis/variance_covariance.h: expectations, EDF and the
/// correlation across τ; analysis::VarianceDraw, the interval draws' χ² marginals joined by a
/// Gaussian copula):
/// the power of the model selection where the term is present and its false rate where it is
/// not, per selection threshold κ and minimum EDF. A study of the selection's statistics with
/// the record's own sampling distribution, not a validation of the estimator (that is the
/// battery's, on independent data: docs/validation.md).
///
///   selection_power [--draws 400] [--seed 1]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "analysis/noise_fit.h"
#include "analysis/tau_grid.h"
#include "analysis/variance_covariance.h"

namespace {

using namespace imunoise;
using namespace imunoise::analysis;

struct Case {
  const char* name;
  NoiseCoefficients truth;
  double rate_hz;
  double hours;
};

}  // namespace

int main(int argc, char** argv) {
  int draws = 400;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--draws")) draws = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--seed")) seed = std::strtoull(argv[i + 1], nullptr, 10);
  }
  // The battery's consumer gyro_x (1 h at 1 kHz) and industrial gyro_x (4 h at 400 Hz), each
  // with K and without it (the null).
  std::vector<Case> cases;
  const auto with_and_without_k = [&cases](const char* name, const char* null_name, double n,
                                           double b, double k, double rate_hz, double hours) {
    Case c{name, {}, rate_hz, hours};
    c.truth.white_noise = n;
    c.truth.bias_instability = b;
    c.truth.random_walk = k;
    cases.push_back(c);
    c.name = null_name;
    c.truth.random_walk = 0.0;
    cases.push_back(c);
  };
  with_and_without_k("consumer gyro_x", "consumer gyro_x, no K", 1.745e-4, 4.848e-5, 4.04e-6,
                     1000.0, 1.0);
  with_and_without_k("industrial gyro_x", "industrial gyro_x, no K", 4.363e-5, 9.696e-6, 4.04e-7,
                     400.0, 4.0);
  const double kappas[] = {12.0, 9.0, 6.6, 4.0};
  const double min_edfs[] = {4.0, 2.0, 1.0};
  for (const Case& c : cases) {
    const double tau0 = 1.0 / c.rate_hz;
    const auto n = static_cast<std::int64_t>(c.hours * 3600.0 * c.rate_hz);
    const std::vector<std::int64_t> m =
        averaging_factors(parse_tau_grid("log:10"), DeviationType::oadev, n + 1);
    const VarianceCovariance vc = overlapping_variance_covariance(c.truth, tau0, n, m);
    const auto k = static_cast<Eigen::Index>(m.size());
    const VarianceDraw draw(vc);
    std::printf("%s: %lld points, tau %.3g..%.3g s, EDF at the last 6:", c.name,
                static_cast<long long>(k), m.front() * tau0, m.back() * tau0);
    for (Eigen::Index i = k - 6; i < k; ++i) std::printf(" %.2f@%.0fs", vc.edf[i], m[i] * tau0);
    std::printf("\n");
    for (double min_edf : min_edfs) {
      for (double kappa : kappas) {
        std::mt19937_64 rng(seed);
        std::normal_distribution<double> normal;
        int k_kept = 0, b_kept = 0, r_kept = 0, q_kept = 0;
        std::vector<double> u(m.size()), y(m.size());
        std::vector<double> k_err;
        for (int r = 0; r < draws; ++r) {
          for (double& x : u) x = normal(rng);
          draw.draw(u, y);
          std::vector<FitPoint> pts;
          for (Eigen::Index i = 0; i < k; ++i) pts.push_back({m[i] * tau0, y[i], vc.edf[i]});
          FitOptions o;
          o.gauss_markov = GaussMarkovMode::off;
          o.selection_threshold = kappa;
          o.min_edf = min_edf;
          const FitResult f = fit_noise_model(pts, o);
          k_kept += f.terms[NoiseTerm::random_walk].identified;
          b_kept += f.terms[NoiseTerm::bias_instability].identified;
          r_kept += f.terms[NoiseTerm::ramp].identified;
          q_kept += f.terms[NoiseTerm::quantization].identified;
          if (f.terms[NoiseTerm::random_walk].identified && c.truth.random_walk > 0)
            k_err.push_back(std::abs(f.coefficients.random_walk / c.truth.random_walk - 1));
        }
        std::sort(k_err.begin(), k_err.end());
        std::printf(
            "  min_edf %.0f kappa %4.1f: K %5.1f %%  B %5.1f %%  R %5.1f %%  Q %5.1f %%  "
            "K median |err| %s\n",
            min_edf, kappa, 100.0 * k_kept / draws, 100.0 * b_kept / draws, 100.0 * r_kept / draws,
            100.0 * q_kept / draws,
            k_err.empty() ? "-" : std::to_string(100 * k_err[k_err.size() / 2]).c_str());
      }
    }
  }
  return 0;
}
