// Throughput of the recording reader on a generated ~100 MB, 7-column CSV in /tmp, written
// like `imunoise simulate` writes (time_s + 3 gyro + 3 accel columns, shortest round-trip
// text, so most values carry 16–17 significant digits). Reports bytes/s; the thread count is
// the benchmark argument (1 and 2), read with the file in the page cache.
#include <benchmark/benchmark.h>

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/csv_reader.h"

namespace {

/// Writes the benchmark file once per process and returns its path.
const std::string& bench_csv() {
  static const std::string path = [] {
    const std::string p =
        (std::filesystem::temp_directory_path() / "imunoise_bench_7col_shortest.csv").string();
    std::FILE* f = std::fopen(p.c_str(), "wb");
    if (f == nullptr) throw std::runtime_error("cannot write " + p);
    std::fputs(
        "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
        "accel_y_m_per_s2,accel_z_m_per_s2\n",
        f);
    std::mt19937_64 rng(42);  // fixed seed: the same file every run
    std::normal_distribution<double> gyro(0.0, 1e-3), accel(0.0, 2e-2);
    constexpr std::size_t kTargetBytes = std::size_t{100} << 20;
    std::size_t written = 0;
    char line[256];
    for (long i = 0; written < kTargetBytes; ++i) {
      const double values[] = {static_cast<double>(i) / 400.0,
                               gyro(rng),
                               gyro(rng),
                               gyro(rng),
                               accel(rng),
                               accel(rng),
                               9.80665 + accel(rng)};
      char* p = line;
      for (std::size_t c = 0; c < std::size(values); ++c) {
        if (c > 0) *p++ = ',';
        p = std::to_chars(p, line + sizeof line, values[c]).ptr;
      }
      *p++ = '\n';
      const auto n = static_cast<std::size_t>(p - line);
      std::fwrite(line, 1, n, f);
      written += n;
    }
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + p);
    return p;
  }();
  return path;
}

std::int64_t file_bytes() {
  return static_cast<std::int64_t>(std::filesystem::file_size(bench_csv()));
}

/// Pure parsing: all 7 columns into vectors (no unit conversion, no report).
void BM_TableReadAllColumns(benchmark::State& state) {
  const std::string& path = bench_csv();
  std::vector<imunoise::io::ColumnRequest> requests;
  for (std::size_t c = 0; c < 7; ++c) requests.push_back({c, c == 0});
  const imunoise::io::ReadParallelism parallelism{.threads = static_cast<unsigned>(state.range(0))};
  for (auto _ : state) {
    imunoise::io::TableReader reader(path);
    const auto data = reader.read(requests, false, {}, parallelism);
    benchmark::DoNotOptimize(data.columns.back().data());
  }
  state.SetBytesProcessed(state.iterations() * file_bytes());
}
BENCHMARK(BM_TableReadAllColumns)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The same, streamed in 1 MiB blocks on one thread: the path small files and pipes take.
void BM_TableReadAllColumnsStreamed(benchmark::State& state) {
  const std::string& path = bench_csv();
  std::vector<imunoise::io::ColumnRequest> requests;
  for (std::size_t c = 0; c < 7; ++c) requests.push_back({c, c == 0});
  const imunoise::io::ReadParallelism streamed{.min_mapped_bytes = SIZE_MAX};
  for (auto _ : state) {
    imunoise::io::TableReader reader(path);
    const auto data = reader.read(requests, false, {}, streamed);
    benchmark::DoNotOptimize(data.columns.back().data());
  }
  state.SetBytesProcessed(state.iterations() * file_bytes());
}
BENCHMARK(BM_TableReadAllColumnsStreamed)->Unit(benchmark::kMillisecond)->UseRealTime();

/// One column (the `allan` path): the other six are split but not converted.
void BM_ReadSeriesOneColumn(benchmark::State& state) {
  const std::string& path = bench_csv();
  imunoise::io::SeriesReadOptions options;
  options.column = "gyro_z_rad_per_s";
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    const auto series = imunoise::io::read_series(path, options);
    benchmark::DoNotOptimize(series.values.data());
  }
  state.SetBytesProcessed(state.iterations() * file_bytes());
}
BENCHMARK(BM_ReadSeriesOneColumn)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Everything `imunoise check` does: parse, SI conversion and the sampling report.
void BM_ReadRecordingWithReport(benchmark::State& state) {
  const std::string& path = bench_csv();
  for (auto _ : state) {
    const auto rec =
        imunoise::io::read_recording(path, {}, {}, static_cast<unsigned>(state.range(0)));
    benchmark::DoNotOptimize(rec.channels.data());
  }
  state.SetBytesProcessed(state.iterations() * file_bytes());
}
BENCHMARK(BM_ReadRecordingWithReport)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
