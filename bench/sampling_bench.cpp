// Sampling checks of `imunoise check` (io/sampling_report) on 11.52 M samples per channel (8 h
// at 400 Hz; a 24 h recording at 1 kHz is 7.5 times longer), against the memory floor: the
// time to read the array once (BM_StreamFloor). Bytes/s reported = 8 bytes × samples, so
// time / floor is how many passes over memory a check costs. 11.52 M doubles (92 MB) are far
// beyond the caches: every pass comes from DRAM, as it does for a real recording.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "io/sampling_report.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define BENCH_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define BENCH_CLONES
#endif

namespace {

constexpr std::size_t kSamples = 11'520'000;

/// Gyro-like white noise, unquantised (σ = 1e-3 rad/s): estimate_lsb finds no grid.
const std::vector<double>& noise_channel() {
  static const std::vector<double> v = [] {
    std::mt19937_64 rng(1);
    std::normal_distribution<double> normal(0.0, 1e-3);
    std::vector<double> x(kSamples);
    for (double& s : x) s = normal(rng);
    return x;
  }();
  return v;
}

/// ADC codes of 1e-3 around a bias, σ = 4 codes (an IMU at rest): neighbours are often equal.
const std::vector<double>& quantized_channel() {
  static const std::vector<double> v = [] {
    std::mt19937_64 rng(2);
    std::normal_distribution<double> normal(0.0, 4.0);
    std::vector<double> x(kSamples);
    for (double& s : x) s = static_cast<double>(std::lround(normal(rng)) + 37) * 1e-3;
    return x;
  }();
  return v;
}

/// 1 kHz time stamps with 2 µs RMS jitter (monotonic; no gaps).
const std::vector<double>& stamps() {
  static const std::vector<double> v = [] {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> jitter(0.0, 2e-6);
    std::vector<double> t(kSamples);
    for (std::size_t i = 0; i < kSamples; ++i) t[i] = static_cast<double>(i) * 1e-3 + jitter(rng);
    return t;
  }();
  return v;
}

void set_bytes(benchmark::State& state) {
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(kSamples * sizeof(double)));
  state.counters["ns_per_sample"] =
      benchmark::Counter(static_cast<double>(kSamples) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// Σ x with sixteen independent accumulators (no add-latency chain), compiled for the same
/// ISAs as the kernels: the fastest way to read the array once.
BENCH_CLONES double stream_sum(const double* x, std::size_t n) {
  double lane[16] = {};
  std::size_t k = 0;
  for (; k + 16 <= n; k += 16) {
    for (int l = 0; l < 16; ++l) lane[l] += x[k + l];
  }
  for (; k < n; ++k) lane[0] += x[k];
  for (int width = 8; width >= 1; width /= 2) {
    for (int l = 0; l < width; ++l) lane[l] += lane[l + width];
  }
  return lane[0];
}

void BM_StreamFloor(benchmark::State& state) {
  const auto& x = noise_channel();
  for (auto _ : state) benchmark::DoNotOptimize(stream_sum(x.data(), x.size()));
  set_bytes(state);
}

void BM_AnalyzeChannelNoise(benchmark::State& state) {
  const imunoise::pipeline::ChannelSamples channel{"gyro_x", "rad/s", noise_channel(), 0.5};
  for (auto _ : state) benchmark::DoNotOptimize(imunoise::pipeline::analyze_channel(channel));
  set_bytes(state);
}

void BM_AnalyzeChannelQuantized(benchmark::State& state) {
  const imunoise::pipeline::ChannelSamples channel{"gyro_x", "rad/s", quantized_channel(), 0.5};
  for (auto _ : state) benchmark::DoNotOptimize(imunoise::pipeline::analyze_channel(channel));
  set_bytes(state);
}

void BM_EstimateLsbQuantized(benchmark::State& state) {
  const auto& x = quantized_channel();
  for (auto _ : state) benchmark::DoNotOptimize(imunoise::pipeline::estimate_lsb(x));
  set_bytes(state);
}

void BM_AnalyzeTiming(benchmark::State& state) {
  const auto& t = stamps();
  for (auto _ : state) benchmark::DoNotOptimize(imunoise::pipeline::analyze_timing(t));
  set_bytes(state);
}

BENCHMARK(BM_StreamFloor)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyzeChannelNoise)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyzeChannelQuantized)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EstimateLsbQuantized)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyzeTiming)->Unit(benchmark::kMillisecond);

}  // namespace
