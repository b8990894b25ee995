/// @file
/// @brief Kasdin–Walter power-law noise generator (see power_law_noise.h).
#include "models/power_law_noise.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <numbers>
#include <random>
#include <string>

#include "common/errors.h"
#include "common/fftw_planner_lock.h"

namespace imunoise::models {
namespace {

void check_alpha(int alpha, const char* where) {
  IMUNOISE_EXPECT(alpha >= -2 && alpha <= 2, std::string(where) +
                                                 ": alpha must be one of 2, 1, 0, -1, -2 (got " +
                                                 std::to_string(alpha) + ")");
}

/// Below this length the O(n²) direct convolution is cheaper than planning FFTs.
constexpr std::size_t kDirectConvolutionMax = 256;

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
template <typename T>
using FftwBuffer = std::unique_ptr<T[], FftwFree>;

/// First n samples of the causal linear convolution of a and b (both of length n), via
/// zero-padded real FFTs of size ≥ 2n so that the circular wrap-around never reaches them.
std::vector<double> causal_convolution_fft(const std::vector<double>& a,
                                           const std::vector<double>& b) {
  const std::size_t n = a.size();
  std::size_t size = 1;
  while (size < 2 * n) size *= 2;
  const std::size_t bins = size / 2 + 1;
  FftwBuffer<double> real(static_cast<double*>(fftw_malloc(sizeof(double) * size)));
  FftwBuffer<fftw_complex> spec_a(
      static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins)));
  FftwBuffer<fftw_complex> spec_b(
      static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins)));
  IMUNOISE_CHECK(real && spec_a && spec_b, InputError,
                 "power_law_noise: out of memory for n=" + std::to_string(n));
  fftw_plan forward = nullptr;
  fftw_plan inverse = nullptr;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    const int isize = static_cast<int>(size);
    forward = fftw_plan_dft_r2c_1d(isize, real.get(), spec_a.get(), FFTW_ESTIMATE);
    inverse = fftw_plan_dft_c2r_1d(isize, spec_a.get(), real.get(), FFTW_ESTIMATE);
  }
  auto load = [&](const std::vector<double>& v) {
    std::copy(v.begin(), v.end(), real.get());
    std::fill(real.get() + n, real.get() + size, 0.0);
  };
  load(b);
  fftw_execute_dft_r2c(forward, real.get(), spec_b.get());
  load(a);
  fftw_execute(forward);  // into spec_a
  for (std::size_t k = 0; k < bins; ++k) {
    const std::complex<double> product = std::complex<double>(spec_a[k][0], spec_a[k][1]) *
                                         std::complex<double>(spec_b[k][0], spec_b[k][1]);
    spec_a[k][0] = product.real();
    spec_a[k][1] = product.imag();
  }
  fftw_execute(inverse);  // c2r overwrites spec_a, writes real
  std::vector<double> out(real.get(), real.get() + n);
  for (double& v : out) v /= static_cast<double>(size);  // FFTW transforms are unnormalised
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(forward);
    fftw_destroy_plan(inverse);
  }
  return out;
}

}  // namespace

std::vector<double> kasdin_walter_coefficients(int alpha, std::size_t n) {
  check_alpha(alpha, "kasdin_walter_coefficients");
  std::vector<double> c(n);
  if (n == 0) return c;
  c[0] = 1.0;
  const double half = 0.5 * static_cast<double>(alpha);
  for (std::size_t k = 1; k < n; ++k) {
    const double kd = static_cast<double>(k);
    c[k] = c[k - 1] * (kd - 1.0 - half) / kd;
  }
  return c;
}

std::vector<double> power_law_noise(int alpha, std::size_t n, std::uint64_t seed, double h) {
  check_alpha(alpha, "power_law_noise");
  IMUNOISE_EXPECT(std::isfinite(h) && h >= 0.0,
                  "power_law_noise: h must be finite and >= 0 (got " + std::to_string(h) + ")");
  // Two-sided discrete PSD of the filtered noise is var(w)·|2 sin πf|^alpha → var(w)(2πf)^alpha
  // at low f (τ0 = 1); one-sided S_y = h·f^alpha then needs var(w) = h / (2 (2π)^alpha).
  const double sigma =
      std::sqrt(h / (2.0 * std::pow(2.0 * std::numbers::pi, static_cast<double>(alpha))));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> white(n);
  for (double& v : white) v = normal(rng);
  if (alpha == 0 || n == 0) return white;
  // The integer exponents have finite or trivial filters: (1 − z⁻¹) and 1/(1 − z⁻¹).
  if (alpha == 2) {
    std::vector<double> y(n);
    y[0] = white[0];
    for (std::size_t k = 1; k < n; ++k) y[k] = white[k] - white[k - 1];
    return y;
  }
  if (alpha == -2) {
    std::vector<double> y(n);
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k) y[k] = (sum += white[k]);
    return y;
  }

  const std::vector<double> c = kasdin_walter_coefficients(alpha, n);
  if (n > kDirectConvolutionMax) return causal_convolution_fft(c, white);
  std::vector<double> y(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j <= k; ++j) sum += c[j] * white[k - j];
    y[k] = sum;
  }
  return y;
}

}  // namespace imunoise::models
