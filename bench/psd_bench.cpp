// The PSD of one channel of 24 h at 1 kHz (86.4 M samples, 659 MiB of float64): the classic
// estimate (welch_psd with the automatic 2^23-point segments, then log_bin) against the
// multi-rate estimate `imunoise analyze` uses (analysis::multirate_psd: 12 levels at
// L = 4096), side by side in one run, one thread each (analyze runs one channel per thread).
// Counters: peak_rss_MiB, the peak resident set of a forked child that runs the estimate once
// (it starts with the parent's pages, the record among them), and extra_MiB, that peak minus
// the peak of a child that does nothing: what the estimate itself adds.
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "analysis/multirate_psd.h"
#include "analysis/psd.h"

namespace {

constexpr std::size_t kSamples = 86'400'000;  // 24 h at 1 kHz
constexpr double kRateHz = 1000.0;

/// A gyro-like channel: white rate noise (N = 1e-4 rad/√s) plus a rate random walk
/// (K = 1e-6 rad/s^{3/2}), fixed seed.
const std::vector<double>& channel() {
  static const std::vector<double> x = [] {
    std::mt19937_64 rng(21);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> v(kSamples);
    const double white = 1e-4 * std::sqrt(kRateHz), step = 1e-6 / std::sqrt(kRateHz);
    double walk = 0.0;
    for (double& s : v) {
      walk += step * normal(rng);
      s = white * normal(rng) + walk;
    }
    return v;
  }();
  return x;
}

/// Peak RSS [MiB] of a child forked now that runs WORK once (nothing when WORK is empty).
double child_peak_rss_mib(const std::function<void()>& work) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (work) work();
    ::_exit(0);
  }
  int status = 0;
  rusage usage{};
  if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid) return -1.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void report_memory(benchmark::State& state, const std::function<void()>& work) {
  const double idle = child_peak_rss_mib({});
  const double peak = child_peak_rss_mib(work);
  state.counters["peak_rss_MiB"] = peak;
  state.counters["extra_MiB"] = peak - idle;
  state.counters["data_MiB"] = static_cast<double>(kSamples * sizeof(double)) / (1 << 20);
}

/// Before: what analyze computed until the multi-rate estimate replaced it.
void classic() {
  const auto spectrum =
      imunoise::analysis::log_bin(imunoise::analysis::welch_psd(channel(), kRateHz));
  benchmark::DoNotOptimize(spectrum.density.data());
}

void multirate() {
  const auto spectrum = imunoise::analysis::multirate_psd(channel(), kRateHz);
  benchmark::DoNotOptimize(spectrum.density.data());
}

void BM_PsdWelchLogBin24h(benchmark::State& state) {
  channel();
  for (auto _ : state) classic();
  report_memory(state, classic);
}

void BM_PsdMultirate24h(benchmark::State& state) {
  channel();
  for (auto _ : state) multirate();
  report_memory(state, multirate);
}

BENCHMARK(BM_PsdWelchLogBin24h)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3);
BENCHMARK(BM_PsdMultirate24h)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3);

}  // namespace
