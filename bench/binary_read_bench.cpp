// Throughput of io::read_binary_recording on a generated .imnb in /tmp: 8 h at 400 Hz,
// time_s + 6 channels (11.52 M samples, 645 MB), read with the file in the page cache, with
// the sampling report (timing + channel checks) as every command gets it. The floor is a copy
// of the same bytes from the page cache into fresh arrays (pread, huge-page advice as the
// reader, no checks), at the same thread count. Bytes/s = file data bytes per read.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/huge_pages.h"
#include "io/binary_recording.h"
#include "pipeline/recording.h"

namespace {

constexpr std::size_t kSamples = 11'520'000;  // 8 h at 400 Hz
constexpr std::size_t kColumns = 7;           // time_s + 6 channels

const std::string& bench_imnb() {
  static const std::string path = [] {
    const std::string p =
        (std::filesystem::temp_directory_path() / "imunoise_bench_8h_400hz.imnb").string();
    imunoise::pipeline::Recording rec;
    rec.source_path = "bench";
    rec.sample_period_s = 1.0 / 400.0;
    std::mt19937_64 rng(7);  // fixed seed: the same file every run
    std::normal_distribution<double> noise(0.0, 1.0);
    rec.time_s.resize(kSamples);
    for (std::size_t i = 0; i < kSamples; ++i) {
      rec.time_s[i] = static_cast<double>(i) / 400.0 + 1e-6 * noise(rng);
    }
    rec.time_s[0] = 0.0;
    const char* names[] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};
    for (std::size_t c = 0; c < 6; ++c) {
      imunoise::pipeline::Channel ch;
      ch.name = names[c];
      ch.kind = imunoise::pipeline::kImuChannelKinds[c];
      ch.values.resize(kSamples);
      const double scale = c < 3 ? 1e-3 : 2e-2;
      for (double& v : ch.values) v = scale * noise(rng);
      rec.channels.push_back(std::move(ch));
    }
    imunoise::io::write_binary_recording(p, rec);
    return p;
  }();
  return path;
}

std::int64_t data_bytes() { return static_cast<std::int64_t>(kSamples * kColumns * 8); }

void BM_BinaryReadRecording(benchmark::State& state) {
  const std::string& path = bench_imnb();
  imunoise::io::BinaryReadOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    const auto rec = imunoise::io::read_binary_recording(path, options);
    benchmark::DoNotOptimize(rec.channels.back().values.data());
  }
  state.SetBytesProcessed(state.iterations() * data_bytes());
}
BENCHMARK(BM_BinaryReadRecording)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The floor: the same bytes pread into fresh arrays, columns split over the threads.
void BM_BinaryCopyFloor(benchmark::State& state) {
  const std::string& path = bench_imnb();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open " + path);
  const auto file_size = static_cast<std::uint64_t>(std::filesystem::file_size(path));
  const std::uint64_t column_bytes = kSamples * 8;
  const std::uint64_t first = file_size - kColumns * ((column_bytes + 63) / 64 * 64);
  const auto threads = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    std::vector<std::vector<double>> columns(kColumns);
    std::vector<std::thread> pool;
    const auto work = [&](std::size_t t) {
      for (std::size_t c = t; c < kColumns; c += threads) {
        imunoise::reserve_huge_pages(columns[c], kSamples);  // as the reader does
        columns[c].resize(kSamples);
        auto* out = reinterpret_cast<char*>(columns[c].data());
        std::uint64_t done = 0;
        while (done < column_bytes) {
          const std::uint64_t want = std::min<std::uint64_t>(column_bytes - done, 1 << 20);
          const ssize_t got =
              ::pread(fd, out + done, want,
                      static_cast<off_t>(first + c * ((column_bytes + 63) / 64 * 64) + done));
          if (got <= 0) throw std::runtime_error("short read");
          done += static_cast<std::uint64_t>(got);
        }
      }
    };
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& t : pool) t.join();
    benchmark::DoNotOptimize(columns.back().data());
  }
  ::close(fd);
  state.SetBytesProcessed(state.iterations() * data_bytes());
}
BENCHMARK(BM_BinaryCopyFloor)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
