#include "report/axis_ticks.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <system_error>
#include <utility>

namespace imunoise::report {
namespace {

constexpr int kMinDecade = -307;  // 1e-307 is still a normal double
constexpr int kMaxDecade = 308;

/// 10^K, correctly rounded (parsed from "1eK", not pow()).
double pow10_exact(int k, int mantissa = 1) {
  char buffer[24];
  char* end = std::to_chars(buffer, buffer + 8, mantissa).ptr;
  *end++ = 'e';
  end = std::to_chars(end, buffer + sizeof buffer, k).ptr;
  double value = 0.0;
  std::from_chars(buffer, end, value);
  return value;
}

/// ⌊log10 V⌋ for V > 0, exact at powers of ten, clamped to the normal-double decades.
int decade_index_floor(double v) {
  if (std::isnan(v) || v <= 1e-307) return kMinDecade;
  if (v >= 1e308) return kMaxDecade;
  int k = static_cast<int>(std::floor(std::log10(v)));
  k = std::clamp(k, kMinDecade, kMaxDecade);
  if (k > kMinDecade && pow10_exact(k) > v) --k;
  if (k < kMaxDecade && pow10_exact(k + 1) <= v) ++k;
  return k;
}

int decade_index_ceil(double v) {
  const int k = decade_index_floor(v);
  return (k < kMaxDecade && pow10_exact(k) < v) ? k + 1 : k;
}

/// Fixed form with at most DECIMALS decimals, trailing zeros removed ("1", "0.2", "0.15").
std::string fixed_text(double v, int decimals) {
  char buffer[400];  // a fixed double can have ~310 integer digits
  char* end =
      std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, decimals).ptr;
  if (decimals > 0) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  return std::string(buffer, end);
}

/// Scientific form with DIGITS after the point, trailing mantissa zeros removed ("1.5e-09").
std::string scientific_text(double v, int digits) {
  char buffer[64];
  const auto r =
      std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::scientific, digits);
  std::string text(buffer, r.ptr);
  const auto e = text.find('e');
  std::size_t mantissa_end = e;
  if (text.find('.') < e) {
    while (text[mantissa_end - 1] == '0') --mantissa_end;
    if (text[mantissa_end - 1] == '.') --mantissa_end;
  }
  text.erase(mantissa_end, e - mantissa_end);
  return text;
}

}  // namespace

double decade_floor(double v) { return pow10_exact(decade_index_floor(v)); }
double decade_ceil(double v) { return pow10_exact(decade_index_ceil(v)); }

std::vector<Tick> linear_ticks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (lo > hi) std::swap(lo, hi);
  target_count = std::clamp(target_count, 2, 50);
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  if (hi - lo <= 1e-12 * magnitude || hi == lo) {  // empty range: widen it
    if (magnitude == 0.0) {
      lo = -1.0;
      hi = 1.0;
    } else {
      const double centre = 0.5 * lo + 0.5 * hi;
      const double half = 0.1 * std::abs(centre);
      lo = centre - half;
      hi = centre + half;
    }
  }
  // Half the width first, so ±1e308 does not overflow.
  const double rough = (0.5 * hi - 0.5 * lo) / (target_count - 1) * 2.0;
  const int e0 =
      std::clamp(static_cast<int>(std::floor(std::log10(rough))), kMinDecade + 1, kMaxDecade - 1);

  int best_m = 0, best_e = 0;
  double best_lo = 0.0, best_count = 0.0, best_distance = 0.0;
  for (int e = e0 - 1; e <= e0 + 1; ++e) {
    for (int m : {1, 2, 5}) {
      const double step = m * pow10_exact(e);
      if (!(step > 0.0) || !std::isfinite(step)) continue;
      const double k_lo = std::floor(lo / step);
      const double k_hi = std::ceil(hi / step);
      const double count = k_hi - k_lo + 1.0;
      const double distance = std::abs(count - target_count);
      if (best_m == 0 || distance < best_distance) {
        best_m = m;
        best_e = e;
        best_lo = k_lo;
        best_count = count;
        best_distance = distance;
      }
    }
  }
  if (best_m == 0 || !(best_count >= 2.0) || best_count > 1000.0) return {};

  // Value k·m·10^e computed as an exact integer times or over an exact power of ten, so
  // 0.6 is 6/10 rather than 3·0.2.
  const double scale = pow10_exact(std::abs(best_e));
  std::vector<Tick> ticks;
  ticks.reserve(static_cast<std::size_t>(best_count));
  for (int i = 0; i < static_cast<int>(best_count); ++i) {
    const double units = (best_lo + i) * best_m;
    double v = best_e < 0 ? units / scale : units * scale;
    if (v == 0.0) v = 0.0;  // no "-0"
    if (!std::isfinite(v)) continue;
    ticks.push_back({v, "", true});
  }
  if (ticks.empty()) return ticks;

  const double largest = std::max(std::abs(ticks.front().value), std::abs(ticks.back().value));
  const bool scientific = largest >= 1e6 || largest < 1e-3;
  const int decimals = std::max(0, -best_e);
  for (auto& t : ticks) {
    if (t.value == 0.0) {
      t.text.assign(1, '0');  // not = "0": GCC 12 false -Wrestrict
    } else if (scientific) {
      t.text =
          scientific_text(t.value, std::max(0, decade_index_floor(std::abs(t.value)) - best_e));
    } else {
      t.text = fixed_text(t.value, decimals);
    }
  }
  return ticks;
}

std::vector<Tick> log10_ticks(double lo, double hi) {
  if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (lo > hi) std::swap(lo, hi);
  int k_lo = decade_index_floor(lo);
  int k_hi = decade_index_ceil(hi);
  if (k_lo == k_hi) {
    k_lo = std::max(kMinDecade, k_lo - 1);
    k_hi = std::min(kMaxDecade, k_hi + 1);
  }
  const int span = k_hi - k_lo;
  const int every = span <= 12 ? 1 : (span + 9) / 10;
  std::vector<Tick> ticks;
  for (int k = k_lo; k <= k_hi; ++k) {
    if (((k % every) + every) % every == 0) {
      std::string text = "10^";  // append(): GCC 12 raises a false -Wrestrict on "…" + string
      text.append(std::to_string(k));
      ticks.push_back({pow10_exact(k), std::move(text), true});
    } else if (span <= 60) {
      ticks.push_back({pow10_exact(k), "", false});
    }
    if (span <= 12 && k < k_hi) {
      for (int m = 2; m <= 9; ++m) ticks.push_back({pow10_exact(k, m), "", false});
    }
  }
  return ticks;
}

}  // namespace imunoise::report
