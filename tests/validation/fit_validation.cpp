/// @file
/// @brief Recovery validation of the noise fit on simulated data with known truth (issue 3):
/// for each scenario, R independent realizations are simulated, analysed exactly as
/// `imunoise analyze` does (pipeline::analyze_axis: OADEV, fit, parametric bootstrap), and the
/// program reports per coefficient the coverage of the intervals, the median relative error,
/// and the bias and spread of the fit next to the IEEE-952 slope read-off.
///
/// Full run (closing-note figures):  fit_validation --realizations 200
///   (intervals as `imunoise analyze` makes them: 200 OAVAR vectors drawn per fit; with
///   --source simulate --bootstrap 50 the reference bootstrap of simulated records)
/// Reduced run (CI, via ctest):      fit_validation --reduced --check
/// --check exits 1 when a coverage falls outside the binomial acceptance band
/// [p − 3·sd − 0.05, p + 3·sd + 0.05]·(coverage of the nominal 95 %), sd = √(p(1−p)/R): with
/// fixed seeds the result is deterministic, the band only decides what counts as a defect.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "common/noise_coefficients.h"
#include "common/units.h"
#include "models/noise_model.h"
#include "models/noise_simulator.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/bootstrap.h"

namespace {

using imunoise::NoiseCoefficients;
using imunoise::NoiseTerm;

struct Scenario {
  const char* name;
  NoiseCoefficients truth;
  bool gauss_markov_fit = false;
};

/// Textbook consumer-MEMS gyro values (theory.md §8.2) and mixes built from them. The
/// quantization level follows the rate so that 3Q²/τ² crosses N²/τ at τ = 4·τ0 at any rate.
std::vector<Scenario> scenarios(double rate_hz) {
  namespace u = imunoise::units;
  const double n = 0.4 * u::kDegPerSqrtHour;  // 1.16355e-4 rad/√s
  const double b = 0.007 * u::kDeg;           // 1.22173e-4 rad/s
  const double k = 3.9e-4 * u::kDeg;          // 6.80678e-6 rad/s^1.5
  std::vector<Scenario> out;
  {
    Scenario s{"white+rw", {}};
    s.truth.white_noise = n;
    s.truth.random_walk = k;
    out.push_back(s);
  }
  {
    Scenario s{"white+flicker+rw", {}};
    s.truth.white_noise = n;
    s.truth.bias_instability = b;
    s.truth.random_walk = k;
    out.push_back(s);
  }
  {
    Scenario s{"white+gm", {}, true};
    s.truth.white_noise = n;
    s.truth.gauss_markov.push_back({2.0e-4, 30.0});
    out.push_back(s);
  }
  {
    Scenario s{"quantization+white+ramp", {}};
    s.truth.quantization = n * std::sqrt(4.0 / (3.0 * rate_hz));  // 3Q²/τ² = N²/τ at τ = 4τ0
    s.truth.white_noise = n;
    s.truth.ramp = 2.0e-8;  // rad/s²: R²τ²/2 = N²/τ at τ = (2N²/R²)^{1/3} ≈ 410 s
    out.push_back(s);
  }
  return out;
}

struct Settings {
  int realizations = 200;
  int bootstrap = 200;
  /// draw: the OAVAR vector from its model distribution; simulate: whole records.
  imunoise::pipeline::ReplicateSource source =
      imunoise::pipeline::ReplicateSource::variance_distribution;
  double duration_s = 8.0 * 3600.0;
  double rate_hz = 100.0;
  unsigned threads = 0;
  bool check = false;
  std::string only;
};

/// Per realization: the fitted estimates with intervals and the slope read-off.
struct Outcome {
  std::array<imunoise::models::Estimate, 5> terms;
  std::array<double, 5> slope{};
  std::vector<imunoise::models::GaussMarkovEstimate> gm;
  bool ok = false;
  std::string error;
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / static_cast<double>(v.size());
}

double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() < 2 ? NAN : std::sqrt(s / static_cast<double>(v.size() - 1));
}

bool run_scenario(const Scenario& scenario, const Settings& settings) {
  const auto n_samples =
      static_cast<std::int64_t>(std::llround(settings.duration_s * settings.rate_hz));
  const double tau0 = 1.0 / settings.rate_hz;
  std::vector<Outcome> outcomes(static_cast<std::size_t>(settings.realizations));
  std::atomic<int> next{0};
  const auto worker = [&] {
    std::vector<double> rate(static_cast<std::size_t>(n_samples));
    for (int r = next++; r < settings.realizations; r = next++) {
      imunoise::models::SimulationOptions sim;
      sim.sample_rate_hz = settings.rate_hz;
      sim.seed = 7919ULL * static_cast<std::uint64_t>(r + 1);
      sim.flicker_band = {tau0, settings.duration_s};
      imunoise::models::ChannelSimulator simulator(
          imunoise::models::channel_model_from(scenario.truth), sim, 0);
      simulator.next_block(rate);
      imunoise::pipeline::AxisAnalysisOptions options;
      options.bootstrap_replicates = settings.bootstrap;
      options.interval_source = settings.source;
      options.seed = 104729ULL + static_cast<std::uint64_t>(r);
      options.fit.gauss_markov = scenario.gauss_markov_fit
                                     ? imunoise::analysis::GaussMarkovMode::on
                                     : imunoise::analysis::GaussMarkovMode::off;
      Outcome& out = outcomes[static_cast<std::size_t>(r)];
      try {
        const auto result = imunoise::pipeline::analyze_axis("gyro_x", imunoise::SensorKind::gyro,
                                                             rate, tau0, 0, options);
        out.terms = result.model.terms;
        out.slope = result.model.readoff.slope;
        out.gm = result.model.gauss_markov;
        out.ok = true;
      } catch (const std::exception& e) {
        out.error = e.what();
      }
    }
  };
  const unsigned threads =
      settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  int ok = 0;
  for (const Outcome& o : outcomes) {
    if (o.ok) {
      ++ok;
    } else {
      std::printf("  realization failed: %s\n", o.error.c_str());
    }
  }
  std::printf("\n== %s: %d realizations (%d analysed), %.0f s at %g Hz, %d interval replicates ==\n",
              scenario.name, settings.realizations, ok, settings.duration_s, settings.rate_hz,
              settings.bootstrap);
  std::printf("  replicates: %s\n",
              settings.source == imunoise::pipeline::ReplicateSource::simulated_record
                  ? "simulated records"
                  : "OAVAR vectors drawn from the model distribution");
  std::printf("  %-17s %10s %9s %9s %9s %9s %11s %11s %11s\n", "term", "true", "coverage", "ident.",
              "med|err|", "fit bias", "fit spread", "slope bias", "slope spr.");
  bool pass = true;
  const auto check_coverage = [&](const char* what, int inside, int total) {
    if (!settings.check || total == 0) return;
    const double p = 0.95;
    const double sd = std::sqrt(p * (1.0 - p) / total);
    const double cov = static_cast<double>(inside) / total;
    if (cov < p - 3.0 * sd - 0.05 || cov > 1.0) {
      std::printf("  CHECK FAILED: %s coverage %.3f outside [%.3f, 1]\n", what, cov,
                  p - 3.0 * sd - 0.05);
      pass = false;
    }
  };
  for (NoiseTerm term : imunoise::kNoiseTerms) {
    const auto t = static_cast<std::size_t>(term);
    const double truth = imunoise::coefficient(scenario.truth, term);
    int inside = 0, identified = 0;
    std::vector<double> rel_fit, rel_slope, abs_err;
    for (const Outcome& o : outcomes) {
      if (!o.ok) continue;
      const auto& e = o.terms[t];
      if (truth >= e.ci_low && truth <= e.ci_high) ++inside;
      if (e.identified) ++identified;
      if (truth > 0.0) {
        rel_fit.push_back(e.value / truth - 1.0);
        abs_err.push_back(std::abs(e.value / truth - 1.0));
        if (o.slope[t] > 0.0) rel_slope.push_back(o.slope[t] / truth - 1.0);
      }
    }
    if (truth > 0.0) {
      std::printf("  %-17s %10.4g %9.3f %5d/%-3d %9.4f %9.4f %11.4f %11.4f %11.4f (n=%zu)\n",
                  std::string(imunoise::term_name(term)).c_str(), truth,
                  static_cast<double>(inside) / ok, identified, ok, median(abs_err), mean(rel_fit),
                  stddev(rel_fit), mean(rel_slope), stddev(rel_slope), rel_slope.size());
      check_coverage(std::string(imunoise::term_name(term)).c_str(), inside, ok);
    } else {
      std::printf("  %-17s %10s %9.3f %5d/%-3d  (absent: coverage = upper bound ≥ 0 holds)\n",
                  std::string(imunoise::term_name(term)).c_str(), "0",
                  static_cast<double>(inside) / ok, identified, ok);
    }
  }
  for (std::size_t j = 0; j < scenario.truth.gauss_markov.size(); ++j) {
    const auto& truth = scenario.truth.gauss_markov[j];
    int inside_s = 0, inside_t = 0, n = 0;
    std::vector<double> err_s, err_t;
    for (const Outcome& o : outcomes) {
      if (!o.ok || o.gm.empty()) continue;
      // The fitted term closest in log T_c to the true one.
      const auto* best = &o.gm.front();
      for (const auto& g : o.gm) {
        if (std::abs(std::log(g.value.tau_c_s / truth.tau_c_s)) <
            std::abs(std::log(best->value.tau_c_s / truth.tau_c_s))) {
          best = &g;
        }
      }
      ++n;
      if (truth.sigma >= best->sigma_ci_low && truth.sigma <= best->sigma_ci_high) ++inside_s;
      if (truth.tau_c_s >= best->tau_c_ci_low_s && truth.tau_c_s <= best->tau_c_ci_high_s) {
        ++inside_t;
      }
      err_s.push_back(std::abs(best->value.sigma / truth.sigma - 1.0));
      err_t.push_back(std::abs(best->value.tau_c_s / truth.tau_c_s - 1.0));
    }
    std::printf("  gm[%zu] sigma %10.4g: coverage %.3f (%d fits with GM), median |err| %.4f\n", j,
                truth.sigma, n ? static_cast<double>(inside_s) / n : NAN, n, median(err_s));
    std::printf("  gm[%zu] tau_c %10.4g s: coverage %.3f, median |err| %.4f\n", j, truth.tau_c_s,
                n ? static_cast<double>(inside_t) / n : NAN, median(err_t));
    check_coverage("gm sigma", inside_s, n);
    check_coverage("gm tau_c", inside_t, n);
  }
  if (settings.check && ok < settings.realizations) {
    std::printf("  CHECK FAILED: %d realizations could not be analysed\n",
                settings.realizations - ok);
    pass = false;
  }
  std::fflush(stdout);
  return pass;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  bool reduced = false, bootstrap_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--realizations") {
      settings.realizations = std::stoi(value());
    } else if (arg == "--bootstrap") {
      settings.bootstrap = std::stoi(value());
      bootstrap_given = true;
    } else if (arg == "--source") {
      const std::string v = value();
      if (v != "draw" && v != "simulate") {
        std::fprintf(stderr, "--source: expected draw or simulate\n");
        return 2;
      }
      settings.source = v == "draw" ? imunoise::pipeline::ReplicateSource::variance_distribution
                                    : imunoise::pipeline::ReplicateSource::simulated_record;
    } else if (arg == "--duration-s") {
      settings.duration_s = std::stod(value());
    } else if (arg == "--rate") {
      settings.rate_hz = std::stod(value());
    } else if (arg == "--threads") {
      settings.threads = static_cast<unsigned>(std::stoul(value()));
    } else if (arg == "--scenario") {
      settings.only = value();
    } else if (arg == "--check") {
      settings.check = true;
    } else if (arg == "--reduced") {
      // CI size: 40 realizations of 4 h at 10 Hz with 40 bootstrap replicates per fit. The
      // τ range, not the rate, decides which terms show: 4 h reach τ = 3600 s, 8× past the
      // RRW/floor crossover (426 s) and the ramp/white crossover (410 s) of the scenarios.
      settings.realizations = 40;
      reduced = true;
      settings.duration_s = 4.0 * 3600.0;
      settings.rate_hz = 10.0;
    } else {
      std::fprintf(
          stderr,
          "usage: fit_validation [--realizations R] [--bootstrap B] [--source draw|simulate] "
          "[--duration-s S] "
          "[--rate HZ] [--threads T] [--scenario NAME] [--reduced] [--check]\n");
      return 2;
    }
  }
  // The reference bootstrap of simulated records costs a record per replicate: 40 in CI.
  if (reduced && !bootstrap_given &&
      settings.source == imunoise::pipeline::ReplicateSource::simulated_record) {
    settings.bootstrap = 40;
  }
  bool pass = true;
  for (const Scenario& s : scenarios(settings.rate_hz)) {
    if (!settings.only.empty() && settings.only != s.name) continue;
    pass = run_scenario(s, settings) && pass;
  }
  return pass ? 0 : 1;
}
