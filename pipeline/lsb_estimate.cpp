/// @file
/// @brief The quantization step of a channel (estimate_lsb), and pass 1 over a channel's samples
/// (extremes, Σ and steps) that analyze_channel shares with it: the vector kernels of both and
/// their AVX2 instances (pipeline/sampling_checks_internal.h), the search over the passes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include "pipeline/lsb_estimate_internal.h"
#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_checks_internal.h"

namespace imunoise::pipeline::detail {

namespace {

constexpr double kMaxLevels = 16777216.0;  // 2^24: no IMU ADC has a finer code grid
constexpr std::size_t kMaxSmallSteps = 4096;

/// Euclid's algorithm on reals with a relative tolerance: stops when the remainder is within
/// 10 % of the divisor, which absorbs decimal printing and float rounding of scaled codes.
double approximate_gcd(double a, double b) {
  if (a < b) std::swap(a, b);
  for (int i = 0; i < 64 && b > 0.0; ++i) {
    const double r = std::fabs(a - b * std::nearbyint(a / b));
    if (r <= 0.1 * b) return b;
    a = b;
    b = r;
  }
  return 0.0;
}

// --- Vector kernels ---------------------------------------------------------------------------

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // see sampling_checks_internal.h

/// Vector accumulators of StepStats. A minimum and a count do not depend on the order, so
/// fewer accumulators than lanes do (registers are scarce: 16 of them).
template <class D>
struct StepLanes {
  D q0[2] = {(D{} + kInf), (D{} + kInf)};
  MaskOf<D> steps = {};

  /// The steps into X (samples) from P (their predecessors); G alternates the minima.
  [[gnu::always_inline]] void add(const D& x, const D& p, double floor, std::size_t g) {
    const D d = vabs(x - p);
    const MaskOf<D> take = d > floor;
    const D candidate = d + (D)(~take & (MaskOf<D>)(D{} + kInf));  // d, or inf
    q0[g % 2] = candidate < q0[g % 2] ? candidate : q0[g % 2];
    steps -= take;
  }
  /// Adds the lanes to S.
  [[gnu::always_inline]] void add_to(StepStats& s) const {
    for (const D& m : q0) {
      for (std::size_t j = 0; j < kWidth<D>; ++j) s.q0 = std::min(s.q0, m[j]);
    }
    for (std::size_t j = 0; j < kWidth<D>; ++j) s.steps += steps[j];
  }
};

/// The steps of V above FLOOR (a pass of their own: see steps_above).
StepStats step_stats(std::span<const double> v, double floor) {
  const std::size_t n = v.size();
  StepLanes<D2> lanes;
  std::size_t i = 1;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t g = 0; g < kGroups<D2>; ++g) {
      const double* x = &v[i + g * kWidth<D2>];
      lanes.add(load<D2>(x), load<D2>(x - 1), floor, g);
    }
  }
  StepStats s;
  for (; i < n; ++i) s.add(std::fabs(v[i] - v[i - 1]), floor);
  lanes.add_to(s);
  return s;
}

/// extremes, on vectors D.
template <class D>
[[gnu::always_inline]] inline Extremes extremes_of(std::span<const double> v) {
  constexpr std::size_t W = kWidth<D>;
  const std::size_t n = v.size();
  Extremes e;
  e.lo = e.hi = v[0];
  double sum[kLanes] = {};
  const auto scalar = [&](std::size_t i) {
    e.lo = std::min(e.lo, v[i]);
    e.hi = std::max(e.hi, v[i]);
    sum[i % kLanes] += v[i];
    if (i > 0) e.nonzero_steps.add(std::fabs(v[i] - v[i - 1]), 0.0);
  };
  std::size_t i = 0;
  for (; i < std::min(n, kLanes); ++i) scalar(i);  // v[0] has no predecessor
  if (i + kLanes <= n) {
    D lo[2] = {(D{} + v[0]), (D{} + v[0])}, hi[2] = {lo[0], lo[0]}, s[kGroups<D>];
    std::memcpy(s, sum, sizeof s);
    StepLanes<D> steps;
    for (; i + kLanes <= n; i += kLanes) {
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const double* p = &v[i + g * W];
        const D x = load<D>(p);
        lo[g % 2] = x < lo[g % 2] ? x : lo[g % 2];
        hi[g % 2] = hi[g % 2] < x ? x : hi[g % 2];
        s[g] += x;
        steps.add(x, load<D>(p - 1), 0.0, g);
      }
    }
    for (std::size_t j = 0; j < 2 * W; ++j) {
      e.lo = std::min(e.lo, lo[j / W][j % W]);
      e.hi = std::max(e.hi, hi[j / W][j % W]);
    }
    std::memcpy(sum, s, sizeof s);
    steps.add_to(e.nonzero_steps);
  }
  for (; i < n; ++i) scalar(i);
  // The lanes lose which of +0 and −0 came first; the fold keeps the first zero.
  if (e.lo == 0.0) e.lo = *std::find(v.begin(), v.end(), 0.0);
  if (e.hi == 0.0) e.hi = *std::find(v.begin(), v.end(), 0.0);
  e.sum = lane_sum(sum);
  return e;
}

/// The first kMaxSmallSteps steps in (noise_floor, limit], in order. Blocks without one are
/// skipped by a vector test: with unquantised data few steps qualify, and the scan reads the
/// whole array.
std::vector<double> small_steps(std::span<const double> v, double noise_floor, double limit) {
  const std::size_t n = v.size();
  std::vector<double> small;
  const auto exact = [&](std::size_t i) {
    const double d = std::fabs(v[i] - v[i - 1]);
    if (d > noise_floor && d <= limit) small.push_back(d);
  };
  std::size_t i = 1;
  for (; i + kLanes <= n && small.size() < kMaxSmallSteps; i += kLanes) {
    MaskOf<D2> hit = {};
    for (std::size_t g = 0; g < kGroups<D2>; ++g) {
      const double* x = &v[i + g * kWidth<D2>];
      const D2 d = vabs(load<D2>(x) - load<D2>(x - 1));
      hit |= (d > noise_floor) & (d <= limit);
    }
    if (!any(hit)) continue;
    for (std::size_t j = i; j < i + kLanes && small.size() < kMaxSmallSteps; ++j) exact(j);
  }
  for (; i < n && small.size() < kMaxSmallSteps; ++i) exact(i);
  return small;
}

/// first_offender, on vectors D.
template <class D>
[[gnu::always_inline]] inline double first_offender_of(std::span<const double> v,
                                                       double noise_floor, double q, double range) {
  const std::size_t n = v.size();
  const std::optional<GridTest> test = grid_test(noise_floor, q, range);
  std::size_t i = 1;
  for (; i + kBlock <= n; i += kBlock) {
    if (test) {
      MaskOf<D> bad = {};
      for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
        bad |= off_grid(vabs(load<D>(&v[j]) - load<D>(&v[j - 1])), *test);
      }
      if (!any(bad)) continue;
    }
    for (std::size_t j = i; j < i + kBlock; ++j) {
      if (const double d = offending_step(v, j, noise_floor, q); d != 0.0) return d;
    }
  }
  for (; i < n; ++i) {
    if (const double d = offending_step(v, i, noise_floor, q); d != 0.0) return d;
  }
  return 0.0;
}

#ifdef IMUNOISE_SAMPLING_AVX2
__attribute__((target("avx2"))) Extremes extremes_avx2(std::span<const double> v) {
  return extremes_of<D4>(v);
}
__attribute__((target("avx2"))) double first_offender_avx2(std::span<const double> v,
                                                           double noise_floor, double q,
                                                           double range) {
  return first_offender_of<D4>(v, noise_floor, q, range);
}
#endif

#pragma GCC diagnostic pop

}  // namespace

// --- Pass 1 -----------------------------------------------------------------------------------

Extremes extremes(std::span<const double> v) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return extremes_avx2(v);
#endif
  return extremes_of<D2>(v);
}

StepStats steps_above(std::span<const double> v, const Extremes& e, double noise_floor) {
  return e.nonzero_steps.q0 > noise_floor ? e.nonzero_steps : step_stats(v, noise_floor);
}

// --- The search over the passes ---------------------------------------------------------------

LsbBounds lsb_bounds(double lo, double hi) {
  LsbBounds b;
  b.range = hi - lo;
  b.usable = b.range > 0.0 && std::isfinite(b.range);
  b.noise_floor = std::max(std::fabs(lo), std::fabs(hi)) * 1e-12;
  return b;
}

std::optional<GridTest> grid_test(double noise_floor, double q, double range) {
  const double inv = 1.0 / q;
  if (!(std::isfinite(inv) && range * inv < 0x1p40)) return std::nullopt;
  return GridTest{noise_floor, q, inv, 0.09 * q};
}

double first_offender(std::span<const double> v, double noise_floor, double q, double range) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return first_offender_avx2(v, noise_floor, q, range);
#endif
  return first_offender_of<D2>(v, noise_floor, q, range);
}

LsbSearch::LsbSearch(std::span<const double> values, const LsbBounds& bounds,
                     const StepStats& stats)
    : range_(bounds.range), noise_floor_(bounds.noise_floor), q_(stats.q0) {
  if (values.size() < 3 || !bounds.usable || stats.steps < 8) return;
  // The first round's range test (q0 > noise_floor by construction), made before the small
  // steps are collected: for unquantised data q0 is tiny and the answer is already known.
  if (range_ / q_ > kMaxLevels) return;
  // The common divisor is searched among small steps (≤ 64 smallest steps): Euclid on a
  // large step would multiply q's rounding error by the step's multiple.
  small_ = small_steps(values, noise_floor_, 64.0 * q_);
  advance();
}

void LsbSearch::resume(double offender) {
  pending_.reset();
  if (offender == 0.0) {
    result_ = q_;
    return;
  }
  q_ = approximate_gcd(q_, offender);
  ++round_;
  advance();
}

void LsbSearch::advance() {
  for (; round_ < 16; ++round_) {
    if (!(q_ > noise_floor_) || range_ / q_ > kMaxLevels) return;
    // First make q divide every small step; q is then still a difference of data values,
    // accurate to their rounding, so refining it cannot pull it off the grid.
    const auto small_offender = std::find_if_not(small_.begin(), small_.end(),
                                                 [&](double d) { return is_multiple(d, q_); });
    if (small_offender != small_.end()) {
      q_ = approximate_gcd(q_, *small_offender);
      continue;
    }
    q_ = refine(q_);
    pending_ = q_;
    return;
  }
}

double LsbSearch::refine(double q) const {
  double sum_d = 0.0, sum_k = 0.0;
  for (double d : small_) {
    if (!is_multiple(d, q)) continue;
    sum_d += d;
    sum_k += std::nearbyint(d / q);
  }
  return sum_k > 0.0 ? sum_d / sum_k : q;
}

}  // namespace imunoise::pipeline::detail

namespace imunoise::pipeline {

std::optional<double> estimate_lsb(std::span<const double> values) {
  if (values.size() < 3) return std::nullopt;
  const detail::Extremes e = detail::extremes(values);
  const detail::LsbBounds bounds = detail::lsb_bounds(e.lo, e.hi);
  if (!bounds.usable) return std::nullopt;
  // The whole search, each full scan a pass of its own.
  detail::LsbSearch search(values, bounds, detail::steps_above(values, e, bounds.noise_floor));
  while (const std::optional<double> q = search.pending()) {
    search.resume(detail::first_offender(values, search.noise_floor(), *q, search.range()));
  }
  return search.result();
}

// GCC 12 reports -Wpsabi for the D4 functions it compiles after parsing at the last token of
// the file: off for that token only, nothing follows (see sampling_checks_internal.h).
#pragma GCC diagnostic ignored "-Wpsabi"
}  // namespace imunoise::pipeline
