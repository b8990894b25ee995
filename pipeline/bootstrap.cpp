#include "pipeline/bootstrap.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>

#include "analysis/chi_square.h"
#include "analysis/deviation.h"
#include "analysis/noise_terms.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"
#include "common/huge_pages.h"
#include "common/parallel_for.h"
#include "models/noise_simulator.h"

namespace imunoise::pipeline {

namespace {

std::uint64_t replicate_seed(std::uint64_t seed, int replicate) {
  // splitmix64 of (seed, replicate): distinct, well-mixed master seeds per replicate.
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(replicate) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

// Bias-corrected normal bootstrap interval of a positive estimate θ̂: in the log domain
// (a scale parameter's error is multiplicative) when every replicate is > 0, centre
// ln θ̂ − (mean ln θ* − ln θ̂), half-width t·sd(ln θ*); else the same in the linear domain,
// clipped at 0. The spread comes from the replicates' standard deviation, not from their
// extreme order statistics: with tens of replicates the 2.5 % / 97.5 % sample quantiles are
// single order statistics and give intervals that cover noticeably less than nominal, while
// the standard deviation is known to ±1/√(2B). t is Student's quantile with B − 1 degrees of
// freedom (Cornish–Fisher: z + (z³ + z)/(4ν)), which accounts for that ±1/√(2B).
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

BootstrapResult bootstrap_fit(const analysis::FitResult& fit,
                              std::span<const analysis::FitPoint> points,
                              std::span<const std::int64_t> m_list, std::int64_t n_samples,
                              double tau0_s, const analysis::FitOptions& fit_options,
                              const BootstrapOptions& options) {
  IMUNOISE_EXPECT(points.size() == m_list.size(),
                  "bootstrap_fit: points and m_list differ in size");
  // `analyze --bootstrap` is checked by the CLI; the axis analysis runs it with >= 2 only.
  IMUNOISE_EXPECT(options.replicates >= 2, "bootstrap: need at least 2 replicates");
  IMUNOISE_EXPECT(n_samples >= 2 && tau0_s > 0.0, "bootstrap: empty record");

  models::ChannelNoiseModel channel = models::channel_model_from(fit.coefficients);
  const double duration_s = static_cast<double>(n_samples) * tau0_s;
  const std::size_t gm_count = fit.coefficients.gauss_markov.size();

  struct Replicate {
    PerTerm<double> terms{};
    std::vector<double> gm_sigma, gm_tau;
    bool ok = false;
  };
  std::vector<Replicate> results(static_cast<std::size_t>(options.replicates));
  std::atomic<int> finished{0};  // for the progress callback only

  // Only the τ the fit used: refit_fixed_terms reads no other point.
  std::vector<std::int64_t> used_m;
  for (std::size_t k : fit.used) used_m.push_back(m_list[k]);

  const bool simulate = options.source == ReplicateSource::simulated_record;
  std::optional<analysis::VarianceDraw> variance_draw;
  if (!simulate) {
    variance_draw.emplace(options.moments != nullptr
                              ? *options.moments
                              : analysis::overlapping_variance_covariance(fit.coefficients, tau0_s,
                                                                          n_samples, used_m));
  }

  // Per worker: one array the record's size, the simulated rate turned into phase in place,
  // so a worker holds 8 bytes per sample (a 24 h record at 1 kHz: 0.7 GB), not 16; and the
  // fit points the replicate's AVAR is written into.
  struct Scratch {
    std::vector<double> samples;
    std::vector<double> normals;  ///< the standard normals of one variance draw
    std::vector<analysis::FitPoint> points;
  };
  const auto make_scratch = [&] {
    Scratch s;
    if (simulate) reserve_huge_pages(s.samples, static_cast<std::size_t>(n_samples) + 1);
    s.points.assign(points.begin(), points.end());
    return s;
  };
  // The OAVAR of replicate R at the τ of FIT.used, written into SCRATCH.points.
  const auto variances = [&](Scratch& scratch, std::size_t r) {
    const std::uint64_t seed = replicate_seed(options.seed, static_cast<int>(r));
    if (!simulate) {
      models::StandardNormal normal{models::Xoshiro256PlusPlus(seed)};
      scratch.samples.resize(used_m.size());
      scratch.normals.resize(used_m.size());
      for (double& u : scratch.normals) u = normal();
      variance_draw->draw(scratch.normals, scratch.samples);
      for (std::size_t i = 0; i < fit.used.size(); ++i) {
        scratch.points[fit.used[i]].avar = scratch.samples[i];
      }
      return;
    }
    models::SimulationOptions sim;
    sim.sample_rate_hz = 1.0 / tau0_s;
    sim.seed = seed;
    sim.flicker_band = {tau0_s, std::max(duration_s, 2.0 * tau0_s)};
    models::ChannelSimulator simulator(channel, sim, 0);
    std::vector<double>& samples = scratch.samples;
    samples.resize(static_cast<std::size_t>(n_samples));
    simulator.next_block(samples);
    analysis::phase_from_rate_in_place(samples, tau0_s);
    // All of them in the shared passes of the OAVAR kernel, equal bit for bit to one
    // allan_family_variance per τ.
    const std::vector<analysis::VarianceEstimate> avar =
        analysis::overlapping_variances(analysis::DeviationType::oadev, samples, used_m, tau0_s);
    for (std::size_t i = 0; i < fit.used.size(); ++i) {
      scratch.points[fit.used[i]].avar = avar[i].variance;
    }
  };
  const auto replicate = [&](Scratch& scratch, std::size_t r) {
    variances(scratch, r);
    Replicate& out = results[r];
    try {
      const analysis::FitResult refit =
          analysis::refit_fixed_terms(scratch.points, fit, fit_options, options.used_correlation);
      for (std::size_t t = 0; t < 5; ++t) out.terms[t] = refit.terms[t].value;
      for (std::size_t j = 0; j < gm_count && j < refit.coefficients.gauss_markov.size(); ++j) {
        out.gm_sigma.push_back(refit.coefficients.gauss_markov[j].sigma);
        out.gm_tau.push_back(refit.coefficients.gauss_markov[j].tau_c_s);
      }
      out.ok = true;
    } catch (const AnalysisError&) {
      out.ok = false;  // counted below; a replicate the estimator cannot fit is dropped
    }
    report_progress(options.progress, "bootstrap", ++finished, options.replicates);
  };
  // Each replicate's numbers depend only on its seed, not on the thread that ran it.
  parallel_for_with_state(results.size(), std::max(1u, options.threads), make_scratch, replicate);

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

}  // namespace imunoise::pipeline
