/// @file
/// @brief Half-band FIR design and polyphase decimation by 2 (see halfband.h).
#include "analysis/halfband.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"

// Compiled for the baseline ISA, x86-64-v3 (AVX2 + FMA) and x86-64-v4 (AVX-512), picked at
// load time, as analysis/difference_sums.cpp does.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define IMUNOISE_HALFBAND_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define IMUNOISE_HALFBAND_CLONES
#endif

namespace imunoise::analysis {
namespace {

constexpr std::size_t kPairs = (kHalfbandTaps + 1) / 4;  // m = 10 non-zero taps per side
constexpr std::size_t kCentre = kHalfbandTaps / 2;       // c = 2m − 1 = 19
constexpr double kKaiserBeta = 15.0;
static_assert(kHalfbandTaps == 4 * kPairs - 1, "a half-band filter has 4m - 1 taps");

struct Design {
  std::array<double, kHalfbandTaps> h{};  // h_0 … h_{N−1}
  std::array<double, kPairs> side{};  // side[i − 1] = h_{c − (2i − 1)} = h_{c + (2i − 1)}
};

/// h_{c+t} = w(t)·sin(πt/2)/(πt) (the ideal low-pass at f_in/4, ½ at t = 0) tapered by the
/// Kaiser window w(t) = I₀(β√(1 − (t/c)²))/I₀(β); then the odd taps scaled to sum to ½, so
/// that H(0) = 1 exactly (the scaling is 1 + O(δ)).
Design make_design() {
  Design d;
  double side_sum = 0.0;
  for (std::size_t i = 1; i <= kPairs; ++i) {
    const double t = static_cast<double>(2 * i - 1);
    const double r = t / static_cast<double>(kCentre);
    const double window =
        std::cyl_bessel_i(0.0, kKaiserBeta * std::sqrt(std::max(0.0, 1.0 - r * r))) /
        std::cyl_bessel_i(0.0, kKaiserBeta);
    d.side[i - 1] = window * std::sin(0.5 * std::numbers::pi * t) / (std::numbers::pi * t);
    side_sum += 2.0 * d.side[i - 1];
  }
  for (double& v : d.side) v *= 0.5 / side_sum;
  d.h[kCentre] = 0.5;
  for (std::size_t i = 1; i <= kPairs; ++i) {
    d.h[kCentre - (2 * i - 1)] = d.side[i - 1];
    d.h[kCentre + (2 * i - 1)] = d.side[i - 1];
  }
  return d;
}

const Design& design() {
  static const Design d = make_design();
  return d;
}

/// Outputs per inner block: the even-phase copy and the accumulators stay in L1 (2 × 4 KiB).
constexpr std::size_t kBlock = 512;

/// y[k] = ½·x[2k + c] + Σ_{i=1}^{m} side_i·(E[k + m − i] + E[k + m − 1 + i]), E[t] = x[2t]:
/// the taps h_{c ∓ (2i − 1)} fall on the even samples 2(k + m − i) and 2(k + m − 1 + i).
IMUNOISE_HALFBAND_CLONES
void decimate_kernel(const double* x, std::size_t outputs, const double* side, double* y) {
  double even[kBlock + 2 * kPairs];
  double acc[kBlock];
  for (std::size_t k0 = 0; k0 < outputs; k0 += kBlock) {
    const std::size_t count = std::min(kBlock, outputs - k0);
    const double* base = x + 2 * k0;
    for (std::size_t t = 0; t + 1 < count + 2 * kPairs; ++t) even[t] = base[2 * t];
    for (std::size_t t = 0; t < count; ++t) acc[t] = 0.5 * base[2 * t + kCentre];
    for (std::size_t i = 1; i <= kPairs; ++i) {
      const double h = side[i - 1];
      const double* lower = even + (kPairs - i);
      const double* upper = even + (kPairs - 1 + i);
      for (std::size_t t = 0; t < count; ++t) acc[t] += h * (lower[t] + upper[t]);
    }
    std::copy(acc, acc + count, y + k0);
  }
}

}  // namespace

std::span<const double> halfband_coefficients() { return design().h; }

std::size_t halfband_outputs(std::size_t inputs) {
  return inputs < kHalfbandTaps ? 0 : (inputs - kHalfbandTaps) / 2 + 1;
}

void halfband_decimate(std::span<const double> x, std::span<double> y) {
  IMUNOISE_EXPECT(y.size() <= halfband_outputs(x.size()),
                  "halfband_decimate: " + std::to_string(y.size()) + " outputs need " +
                      std::to_string(y.empty() ? 0 : 2 * (y.size() - 1) + kHalfbandTaps) +
                      " inputs (got " + std::to_string(x.size()) + ")");
  if (y.empty()) return;
  decimate_kernel(x.data(), y.size(), design().side.data(), y.data());
}

}  // namespace imunoise::analysis
