// Deviation kernels on 11.52 M samples (8 h at 400 Hz), octave and log:10 grids,
// single-threaded, plus the memory-streaming floor (one read pass per τ) for comparison.
// Bytes/s reported = 8 bytes × phase samples × number of τ (one logical pass per τ).
#include <benchmark/benchmark.h>

#include <numeric>
#include <random>

#include "analysis/deviation.h"
#include "analysis/tau_grid.h"

namespace {

using imunoise::analysis::DeviationType;

constexpr std::size_t kSamples = 11'520'000;  // 8 h at 400 Hz

const std::vector<double>& bench_phase() {
  static const std::vector<double> phase = [] {
    std::mt19937_64 rng(1);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> y(kSamples);
    for (double& v : y) v = normal(rng);
    return imunoise::analysis::phase_from_rate(y, 1.0 / 400.0);
  }();
  return phase;
}

void run_curve(benchmark::State& state, DeviationType type, const char* grid, bool with_ci) {
  const auto& phase = bench_phase();
  const auto factors = imunoise::analysis::averaging_factors(
      imunoise::analysis::parse_tau_grid(grid), type, static_cast<std::int64_t>(phase.size()));
  for (auto _ : state) {
    if (with_ci) {
      imunoise::analysis::DeviationOptions options;
      options.type = type;
      options.threads = static_cast<unsigned>(state.range(0));
      benchmark::DoNotOptimize(
          imunoise::analysis::compute_deviation(phase, 1.0 / 400.0, factors, options));
    } else {
      double sink = 0;
      for (auto m : factors) {
        sink += imunoise::analysis::allan_family_variance(type, phase, m, 1.0 / 400.0).variance;
      }
      benchmark::DoNotOptimize(sink);
    }
  }
  state.counters["taus"] = static_cast<double>(factors.size());
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(factors.size() * phase.size() * sizeof(double)));
}

void BM_OadevOctave(benchmark::State& s) { run_curve(s, DeviationType::oadev, "octave", false); }
void BM_OadevLog10(benchmark::State& s) { run_curve(s, DeviationType::oadev, "log:10", false); }
void BM_OhdevOctave(benchmark::State& s) { run_curve(s, DeviationType::ohdev, "octave", false); }
void BM_OhdevLog10(benchmark::State& s) { run_curve(s, DeviationType::ohdev, "log:10", false); }
void BM_HdevOctave(benchmark::State& s) { run_curve(s, DeviationType::hdev, "octave", false); }
void BM_HdevLog10(benchmark::State& s) { run_curve(s, DeviationType::hdev, "log:10", false); }
void BM_MdevLog10(benchmark::State& s) { run_curve(s, DeviationType::mdev, "log:10", false); }
void BM_TotdevLog10(benchmark::State& s) { run_curve(s, DeviationType::totdev, "log:10", false); }
// Full curve: deviations + noise identification + EDF + CI, with N threads.
void BM_OadevLog10WithCi(benchmark::State& s) {
  run_curve(s, DeviationType::oadev, "log:10", true);
}

// The memory floor: stream the phase array once per τ of the log:10 grid (a plain sum).
void BM_StreamFloorLog10(benchmark::State& state) {
  const auto& phase = bench_phase();
  const auto factors = imunoise::analysis::averaging_factors(
      imunoise::analysis::parse_tau_grid("log:10"), DeviationType::oadev,
      static_cast<std::int64_t>(phase.size()));
  for (auto _ : state) {
    double sink = 0;
    for (std::size_t t = 0; t < factors.size(); ++t) {
      double s = 0;
#pragma omp simd reduction(+ : s)
      for (std::size_t k = 0; k < phase.size(); ++k) s += phase[k];
      sink += s;
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(factors.size() * phase.size() * sizeof(double)));
}

BENCHMARK(BM_OadevOctave)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OadevLog10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OhdevOctave)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OhdevLog10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HdevOctave)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HdevLog10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MdevLog10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TotdevLog10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OadevLog10WithCi)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StreamFloorLog10)->Unit(benchmark::kMillisecond);

}  // namespace
