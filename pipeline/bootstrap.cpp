#include "pipeline/bootstrap.h"

#include <algorithm>
#include <atomic>
#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "analysis/chi_square.h"
#include "analysis/deviation.h"
#include "analysis/nnls.h"
#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "models/noise_simulator.h"

namespace imunoise::pipeline {

namespace {

/// Bias-corrected normal bootstrap interval of a positive estimate θ̂: in the log domain
/// (a scale parameter's error is multiplicative) when every replicate is > 0, centre
/// ln θ̂ − (mean ln θ* − ln θ̂), half-width t·sd(ln θ*); else the same in the linear domain,
/// clipped at 0. The spread comes from the replicates' standard deviation, not from their
/// extreme order statistics: with tens of replicates the 2.5 % / 97.5 % sample quantiles are
/// single order statistics and give intervals that cover noticeably less than nominal, while
/// the standard deviation is known to ±1/√(2B). t is Student's quantile with B − 1 degrees of
/// freedom (Cornish–Fisher: z + (z³ + z)/(4ν)), which accounts for that ±1/√(2B).
Interval bootstrap_interval(double estimate, const std::vector<double>& samples,
                            double confidence) {
  const std::size_t b = samples.size();
  if (b < 2) return {estimate, estimate};
  const double z = std::sqrt(analysis::chi_square_quantile(confidence, 1.0));
  const double nu = static_cast<double>(b - 1);
  const double t = z + (z * z * z + z) / (4.0 * nu);
  const bool positive = estimate > 0.0 && std::all_of(samples.begin(), samples.end(),
                                                      [](double v) { return v > 0.0; });
  const auto transform = [positive](double v) { return positive ? std::log(v) : v; };
  double mean = 0.0;
  for (double v : samples) mean += transform(v);
  mean /= static_cast<double>(b);
  double ss = 0.0;
  for (double v : samples) ss += (transform(v) - mean) * (transform(v) - mean);
  const double sd = std::sqrt(ss / nu);
  const double centre = 2.0 * transform(estimate) - mean;
  if (positive) return {std::exp(centre - t * sd), std::exp(centre + t * sd)};
  return {std::max(0.0, centre - t * sd), std::max(0.0, centre + t * sd)};
}

std::uint64_t replicate_seed(std::uint64_t seed, int replicate) {
  // splitmix64 of (seed, replicate): distinct, well-mixed master seeds per replicate.
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(replicate) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

BootstrapResult bootstrap_fit(const analysis::FitResult& fit,
                              std::span<const analysis::FitPoint> points,
                              std::span<const std::int64_t> m_list, std::int64_t n_samples,
                              double tau0_s, const analysis::FitOptions& fit_options,
                              const BootstrapOptions& options) {
  if (points.size() != m_list.size()) {
    throw std::invalid_argument("bootstrap_fit: points and m_list differ in size");
  }
  if (options.replicates < 2) throw InputError("bootstrap: need at least 2 replicates");
  if (n_samples < 2 || !(tau0_s > 0.0)) throw InputError("bootstrap: empty record");

  models::ChannelNoiseModel channel = models::channel_model_from(fit.coefficients);
  const double duration_s = static_cast<double>(n_samples) * tau0_s;
  const std::size_t gm_count = fit.coefficients.gauss_markov.size();

  struct Replicate {
    std::array<double, 5> terms{};
    std::vector<double> gm_sigma, gm_tau;
    bool ok = false;
  };
  std::vector<Replicate> results(static_cast<std::size_t>(options.replicates));
  std::atomic<int> next{0};

  const auto worker = [&] {
    std::vector<double> rate(static_cast<std::size_t>(n_samples));
    std::vector<analysis::FitPoint> replicate_points(points.begin(), points.end());
    for (int r = next++; r < options.replicates; r = next++) {
      models::SimulationOptions sim;
      sim.sample_rate_hz = 1.0 / tau0_s;
      sim.seed = replicate_seed(options.seed, r);
      sim.flicker_band = {tau0_s, std::max(duration_s, 2.0 * tau0_s)};
      models::ChannelSimulator simulator(channel, sim, 0);
      simulator.next_block(rate);
      const std::vector<double> phase = analysis::phase_from_rate(rate, tau0_s);
      for (std::size_t k = 0; k < m_list.size(); ++k) {
        replicate_points[k].avar =
            analysis::allan_family_variance(analysis::DeviationType::oadev, phase, m_list[k],
                                            tau0_s)
                .variance;
      }
      Replicate& out = results[static_cast<std::size_t>(r)];
      try {
        const analysis::FitResult refit =
            analysis::refit_fixed_terms(replicate_points, fit, fit_options);
        for (std::size_t t = 0; t < 5; ++t) out.terms[t] = refit.terms[t].value;
        for (std::size_t j = 0; j < gm_count && j < refit.coefficients.gauss_markov.size(); ++j) {
          out.gm_sigma.push_back(refit.coefficients.gauss_markov[j].sigma);
          out.gm_tau.push_back(refit.coefficients.gauss_markov[j].tau_c_s);
        }
        out.ok = true;
      } catch (const AnalysisError&) {
        out.ok = false;  // counted below; a replicate the estimator cannot fit is dropped
      }
    }
  };
  const unsigned threads = std::max(1u, std::min<unsigned>(options.threads,
                                                           static_cast<unsigned>(options.replicates)));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  BootstrapResult result;
  std::array<std::vector<double>, 5> per_term;
  std::vector<std::vector<double>> gm_sigma(gm_count), gm_tau(gm_count);
  for (const Replicate& rep : results) {
    if (!rep.ok) continue;
    ++result.replicates;
    result.term_samples.push_back(rep.terms);
    for (std::size_t t = 0; t < 5; ++t) per_term[t].push_back(rep.terms[t]);
    if (rep.gm_sigma.size() == gm_count) {
      for (std::size_t j = 0; j < gm_count; ++j) {
        gm_sigma[j].push_back(rep.gm_sigma[j]);
        gm_tau[j].push_back(rep.gm_tau[j]);
      }
    }
  }
  if (result.replicates < 2) {
    throw AnalysisError("bootstrap: the fit failed on " +
                        std::to_string(options.replicates - result.replicates) + " of " +
                        std::to_string(options.replicates) + " simulated replicates");
  }
  for (std::size_t t = 0; t < 5; ++t) {
    result.terms[t] = bootstrap_interval(fit.terms[t].value, per_term[t], options.confidence);
  }
  for (std::size_t j = 0; j < gm_count; ++j) {
    result.gauss_markov_sigma.push_back(bootstrap_interval(fit.coefficients.gauss_markov[j].sigma,
                                                       gm_sigma[j], options.confidence));
    result.gauss_markov_tau_c.push_back(bootstrap_interval(fit.coefficients.gauss_markov[j].tau_c_s,
                                                       gm_tau[j], options.confidence));
  }
  return result;
}

namespace {

/// Gamma deviance Σ ν(r − 1 − ln r), r = σ̂²/model, over the used points (as the fit's).
double deviance_of(std::span<const analysis::FitPoint> points, std::span<const std::size_t> used,
                   const std::vector<double>& model) {
  double d = 0.0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    const analysis::FitPoint& p = points[used[i]];
    if (!(model[i] > 0.0) || !(p.avar > 0.0)) return std::numeric_limits<double>::infinity();
    const double r = p.avar / model[i];
    d += p.edf * (r - 1.0 - std::log(r));
  }
  return d;
}

}  // namespace

double unidentified_upper_bound(analysis::NoiseTerm term, const analysis::FitResult& fit,
                                std::span<const analysis::FitPoint> points, double confidence) {
  // Profile bound: force the term at c, re-fit the other identified terms (NNLS with the
  // fit's model-based weights, GM T_c and sinusoid frequencies held), and find the c at which
  // the deviance has risen by χ²₁(confidence)·n_used/n_eff — the same correlation-corrected
  // scale as the fit's model selection (about one independent point per octave of τ).
  const std::vector<std::size_t>& used = fit.used;
  if (used.empty()) return std::numeric_limits<double>::infinity();
  const auto basis_of = [&](analysis::NoiseTerm t, double tau) {
    return fit.hadamard ? analysis::term_hvar_basis(t, tau) : analysis::term_avar_basis(t, tau);
  };
  std::vector<std::function<double(double)>> columns;
  for (analysis::NoiseTerm t : analysis::kNoiseTerms) {
    if (t == term || !fit.terms[static_cast<std::size_t>(t)].identified) continue;
    columns.emplace_back([&, t](double tau) { return basis_of(t, tau); });
  }
  for (const GaussMarkov& gm : fit.coefficients.gauss_markov) {
    const double tc = gm.tau_c_s;
    const bool h = fit.hadamard;
    columns.emplace_back([tc, h](double tau) {
      return h ? analysis::gauss_markov_hvar(1.0, tc, tau) : analysis::gauss_markov_avar(1.0, tc, tau);
    });
  }
  for (const Sinusoid& line : fit.coefficients.sinusoids) {
    const double f = line.frequency_hz;
    const bool h = fit.hadamard;
    columns.emplace_back([f, h](double tau) {
      return h ? analysis::sinusoid_hvar(1.0, f, tau) : analysis::sinusoid_avar(1.0, f, tau);
    });
  }
  const auto n = static_cast<Eigen::Index>(used.size());
  const auto k = static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd psi(n, k);
  Eigen::VectorXd phi(n), avar(n), weight_base(n);
  std::vector<double> model0(used.size());
  for (Eigen::Index i = 0; i < n; ++i) {
    const analysis::FitPoint& p = points[used[static_cast<std::size_t>(i)]];
    for (Eigen::Index j = 0; j < k; ++j) psi(i, j) = columns[static_cast<std::size_t>(j)](p.tau_s);
    phi(i) = basis_of(term, p.tau_s);
    avar(i) = p.avar;
    weight_base(i) = std::max(p.edf, 0.0) / 2.0;
    model0[static_cast<std::size_t>(i)] =
        fit.hadamard ? analysis::model_hvar(fit.coefficients, p.tau_s)
                     : analysis::model_avar(fit.coefficients, p.tau_s);
  }
  const double d0 = deviance_of(points, used, model0);
  const double scale = static_cast<double>(used.size()) / std::max(1.0, fit.effective_points);
  const double target = analysis::chi_square_quantile(confidence, 1.0) * scale;

  // Deviance with the term forced at c²·φ and the others re-fitted (two re-weightings).
  const auto deviance_at = [&](double c) {
    std::vector<double> model = model0;
    for (int iteration = 0; iteration < 3; ++iteration) {
      Eigen::VectorXd sw(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        sw(i) = std::sqrt(weight_base(i)) / model[static_cast<std::size_t>(i)];
      }
      Eigen::VectorXd a = Eigen::VectorXd::Zero(k);
      if (k > 0) {
        a = analysis::nnls(sw.asDiagonal() * psi, sw.cwiseProduct(avar - c * c * phi));
      }
      for (Eigen::Index i = 0; i < n; ++i) {
        const double m = c * c * phi(i) + (k > 0 ? psi.row(i).dot(a) : 0.0);
        model[static_cast<std::size_t>(i)] = std::max(m, 1e-300);
      }
    }
    return deviance_of(points, used, model);
  };
  // Bracket: at c_hi the term alone is 100× the data at its most favourable point.
  double c_hi = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (phi(i) > 0.0) c_hi = std::max(c_hi, std::sqrt(100.0 * avar(i) / phi(i)));
  }
  if (!(c_hi > 0.0) || !(deviance_at(c_hi) - d0 > target)) {
    return std::numeric_limits<double>::infinity();
  }
  double c_lo = 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (c_lo + c_hi);
    if (deviance_at(mid) - d0 > target) {
      c_hi = mid;
    } else {
      c_lo = mid;
    }
  }
  return c_hi;
}

}  // namespace imunoise::pipeline
