#include "battery/expected_avar.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

namespace imunoise::battery {

namespace {

constexpr long double kPiL = std::numbers::pi_v<long double>;

}  // namespace

std::vector<double> overlapping_avars(std::span<const double> y, std::span<const std::size_t> ms) {
  const std::size_t n = y.size();
  long double mean = 0.0L;
  for (double v : y) mean += v;
  mean /= static_cast<long double>(n);
  std::vector<long double> theta(n + 1);
  theta[0] = 0.0L;
  for (std::size_t i = 0; i < n; ++i) theta[i + 1] = theta[i] + (y[i] - mean);
  std::vector<double> out;
  for (std::size_t m : ms) {
    if (m == 0 || n < 2 * m) throw std::invalid_argument("overlapping_avar: need n >= 2m >= 2");
    const std::size_t terms = n + 1 - 2 * m;
    long double sum = 0.0L;
    for (std::size_t k = 0; k < terms; ++k) {
      const long double d = theta[k + 2 * m] - 2.0L * theta[k + m] + theta[k];
      sum += d * d;
    }
    const long double mm = static_cast<long double>(m);
    out.push_back(static_cast<double>(sum / (2.0L * mm * mm * static_cast<long double>(terms))));
  }
  return out;
}

double overlapping_avar(std::span<const double> y, std::size_t m) {
  const std::size_t ms[] = {m};
  return overlapping_avars(y, ms).front();
}

double white_avar(double n, double tau_s) { return n * n / tau_s; }

double quantization_avar(double q, double tau_s) { return 3.0 * q * q / (tau_s * tau_s); }

double random_walk_avar(double k, double tau0_s, std::size_t m) {
  const double md = static_cast<double>(m);
  return k * k * tau0_s * (2.0 * md * md + 1.0) / (6.0 * md);
}

double ramp_avar(double r, double tau_s) { return r * r * tau_s * tau_s / 2.0; }

double gauss_markov_avar(double sigma, double tau_c_s, double tau0_s, std::size_t m) {
  const long double phi = std::exp(-static_cast<long double>(tau0_s) / tau_c_s);
  const long double one_minus = -std::expm1(-static_cast<long double>(tau0_s) / tau_c_s);
  const long double mm = static_cast<long double>(m);
  const long double sw2 = static_cast<long double>(sigma) * sigma * (1.0L - phi * phi);
  const long double num = mm - 3.0L * phi - mm * phi * phi + 4.0L * std::pow(phi, mm + 1.0L) -
                          std::pow(phi, 2.0L * mm + 1.0L);
  return static_cast<double>(sw2 * num / (mm * mm * one_minus * one_minus * (1.0L - phi * phi)));
}

double sinusoid_avar(double a, double f_hz, double tau0_s, std::size_t m) {
  const long double x = kPiL * f_hz * tau0_s;
  const long double mm = static_cast<long double>(m);
  const long double s1 = std::sin(x), sm = std::sin(mm * x);
  return static_cast<double>(a * a * sm * sm * sm * sm / (mm * mm * s1 * s1));
}

double flicker_avar(double b, std::size_t length, std::size_t m, std::size_t stride) {
  // Phases reduced exactly in integers: j·s·m mod L (fits 64 bits for every size used).
  const std::uint64_t l = length;
  const long double mm = static_cast<long double>(m);
  long double sum = 0.0L;
  for (std::uint64_t j = 1; j < l / 2; ++j) {
    const std::uint64_t js = (j * stride) % l;
    if (js == 0) continue;  // sin⁴(mx)/sin²(x) → 0 at x = 0
    const std::uint64_t jsm = (js * m) % l;
    const long double s1 = std::sin(kPiL * static_cast<long double>(js) / l);
    const long double sm = std::sin(kPiL * static_cast<long double>(jsm) / l);
    const long double c2 = static_cast<long double>(b) * b / (kPiL * static_cast<long double>(j));
    sum += 2.0L * c2 * sm * sm * sm * sm / (mm * mm * s1 * s1);
  }
  return static_cast<double>(sum);
}

double stationary_avar(std::span<const double> autocov, std::size_t m) {
  const auto r = [&](std::size_t l) { return l < autocov.size() ? autocov[l] : 0.0; };
  const long double mm = static_cast<long double>(m);
  long double sum = 2.0L * mm * r(0);
  for (std::size_t l = 1; l <= 2 * m && l < autocov.size(); ++l) {
    const long double w = l <= m ? 2.0L * mm - 3.0L * l : static_cast<long double>(l) - 2.0L * mm;
    sum += 2.0L * w * r(l);  // lags ±l
  }
  return static_cast<double>(sum / (2.0L * mm * mm));
}

double warmup_oavar(double a, double tau_w_s, double tau0_s, std::size_t n, std::size_t m) {
  // y_k = a r^k: θ_{k+2m} − 2θ_{k+m} + θ_k = −a r^k S_m (1 − r^m), S_m = (1 − r^m)/(1 − r);
  // Σ_{k<K} over K = n + 1 − 2m terms of the square, divided by 2m²K.
  const long double q = static_cast<long double>(tau0_s) / tau_w_s;
  const long double mm = static_cast<long double>(m);
  const long double one_minus_rm = -std::expm1(-q * mm);
  const long double sm = one_minus_rm / -std::expm1(-q);
  const long double terms = static_cast<long double>(n + 1 - 2 * m);
  const long double geometric = -std::expm1(-2.0L * q * terms) / -std::expm1(-2.0L * q);
  const long double d0 = static_cast<long double>(a) * sm * one_minus_rm;
  return static_cast<double>(d0 * d0 * geometric / (2.0L * mm * mm * terms));
}

std::vector<double> filtered_white_autocov(const std::array<double, 5>& c) {
  std::vector<double> h;
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0, peak = 0.0;
  for (std::size_t k = 0; k < 1000000; ++k) {
    const double x = k == 0 ? 1.0 : 0.0;
    const double y = c[0] * x + c[1] * x1 + c[2] * x2 - c[3] * y1 - c[4] * y2;
    x2 = x1;
    x1 = x;
    y2 = y1;
    y1 = y;
    h.push_back(y);
    peak = std::max(peak, std::abs(y));
    if (k > 8 && std::abs(y) < 1e-17 * peak && std::abs(y2) < 1e-17 * peak) break;
  }
  std::vector<double> r(h.size());
  for (std::size_t l = 0; l < h.size(); ++l) {
    long double s = 0.0L;
    for (std::size_t k = 0; k + l < h.size(); ++k) s += static_cast<long double>(h[k]) * h[k + l];
    r[l] = static_cast<double>(s);
  }
  return r;
}

double aliased_white_gain(std::span<const double> autocov, std::size_t d) {
  long double s = autocov.empty() ? 0.0L : autocov[0];
  for (std::size_t l = d; l < autocov.size(); l += d) s += 2.0L * autocov[l];
  return static_cast<double>(s);
}

}  // namespace imunoise::battery
