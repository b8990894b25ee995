/// @file
/// @brief The thresholds of the warm-up scan (pipeline::start_transient_threshold): the 99.5 %
/// point of its statistic on stationary noise, per channel count, for each of four noise colours
/// — white; white plus a random walk carrying 60 % of the AVAR at T/10; white plus a
/// flicker-like sum of five first-order Gauss–Markov terms, one per decade of correlation time,
/// at two levels (the sum below and above the white AVAR at T/16). The statistic is a ratio of
/// differences of means to their model scatter in the same channel, so neither the noise level
/// nor the record length enters beyond the block structure; the threshold is the largest point
/// over the colours, rounded up (start_transient.cpp). A study tool, not a test:
/// tests/pipeline/start_transient_test.cpp re-measures the false-alarm rate on fresh seeds.
///
///   start_transient_calibration [--recordings 4000] [--samples 8192] [--seed 1]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "pipeline/start_transient.h"

namespace {

using namespace imunoise;

enum class Colour { white, random_walk, flicker_weak, flicker_strong };
constexpr std::array<Colour, 4> kColours = {Colour::white, Colour::random_walk,
                                            Colour::flicker_weak, Colour::flicker_strong};
const char* colour_name(Colour c) {
  switch (c) {
    case Colour::white:
      return "white";
    case Colour::random_walk:
      return "white+rw";
    case Colour::flicker_weak:
      return "white+gm5(0.01)";
    case Colour::flicker_strong:
      return "white+gm5(1)";
  }
  return "?";
}

/// One channel of N samples, unit white σ per sample plus the colour's term.
void fill(std::vector<double>& x, Colour colour, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  const std::size_t n = x.size();
  // RW: K² per sample² = 4.5/(T/10)², so K²τ/3 = 1.5·σ²/τ at τ = T/10 (60 % of the AVAR).
  const double rw_step = std::sqrt(4.5) / (static_cast<double>(n) / 10.0);
  const double gm_variance = colour == Colour::flicker_strong ? 1.0 : 0.01;
  std::array<double, 5> phi{}, gm_state{}, gm_drive{};
  for (std::size_t k = 0; k < 5; ++k) {
    const double tc = std::pow(10.0, static_cast<double>(k + 1));  // samples
    phi[k] = std::exp(-1.0 / tc);
    gm_drive[k] = std::sqrt(gm_variance * (1.0 - phi[k] * phi[k]));
    gm_state[k] = std::sqrt(gm_variance) * normal(rng);  // stationary start
  }
  double walk = 0.0;
  for (double& v : x) {
    v = normal(rng);
    if (colour == Colour::random_walk) {
      walk += rw_step * normal(rng);
      v += walk;
    }
    if (colour == Colour::flicker_weak || colour == Colour::flicker_strong) {
      for (std::size_t k = 0; k < 5; ++k) {
        gm_state[k] = phi[k] * gm_state[k] + gm_drive[k] * normal(rng);
        v += gm_state[k];
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int recordings = 4000;
  std::size_t samples = 8192;
  unsigned seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--recordings") == 0) recordings = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--samples") == 0) samples = std::strtoul(argv[i + 1], nullptr, 10);
    if (std::strcmp(argv[i], "--seed") == 0) seed = static_cast<unsigned>(std::atoi(argv[i + 1]));
  }
  constexpr std::size_t kMaxChannels = 6;
  std::printf(
      "colour            99.5 %% point of the statistic for K = 1 … 6 channels (%d "
      "recordings of %zu samples)\n",
      recordings, samples);
  std::array<double, kMaxChannels> worst{};
  for (const Colour colour : kColours) {
    std::mt19937_64 rng(seed * 1000003u + static_cast<unsigned>(colour));
    std::array<std::vector<double>, kMaxChannels> statistic;
    std::vector<std::vector<double>> channels(kMaxChannels, std::vector<double>(samples));
    const std::vector<std::string> names(kMaxChannels, "gyro_x");
    for (int r = 0; r < recordings; ++r) {
      for (auto& c : channels) fill(c, colour, rng);
      for (std::size_t k = 1; k <= kMaxChannels; ++k) {
        std::vector<std::span<const double>> spans(channels.begin(),
                                                   channels.begin() + static_cast<long>(k));
        const pipeline::StartTransient s = pipeline::detect_start_transient(
            spans, std::span<const std::string>(names.data(), k), 0.01);
        statistic[k - 1].push_back(s.statistic);
      }
    }
    std::printf("%-17s", colour_name(colour));
    for (std::size_t k = 0; k < kMaxChannels; ++k) {
      std::vector<double>& v = statistic[k];
      const auto at =
          static_cast<std::ptrdiff_t>(std::ceil(0.995 * static_cast<double>(v.size())) - 1);
      std::nth_element(v.begin(), v.begin() + at, v.end());
      worst[k] = std::max(worst[k], v[static_cast<std::size_t>(at)]);
      std::printf(" %7.2f", v[static_cast<std::size_t>(at)]);
    }
    std::printf("\n");
  }
  std::printf("%-17s", "largest");
  for (double w : worst) std::printf(" %7.2f", w);
  std::printf("\n");
  return 0;
}
