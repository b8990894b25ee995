/// @file
/// @brief Internal to pipeline/lsb_estimate.cpp and pipeline/channel_checks.cpp: pass 1 over a
/// channel's samples (extremes, Σ and steps), which both checks start from, and the search for
/// the quantization step in the form analyze_channel drives: its scan of all steps for the
/// first one off a grid rides along in the channel's second pass. Not part of the public API
/// (pipeline/sampling_checks.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pipeline/sampling_checks_internal.h"

namespace imunoise::pipeline::detail {

/// @name Pass 1
/// @{

/// The smallest step |v[i] − v[i−1]| above a floor, and how many steps are above it.
struct StepStats {
  double q0 = kInf;
  std::int64_t steps = 0;

  void add(double d, double floor) {
    if (d > floor) {
      q0 = std::min(q0, d);
      ++steps;
    }
  }
};

/// Pass 1 over a channel's samples: the extremes, the sum and the nonzero steps.
struct Extremes {
  double lo = 0.0, hi = 0.0, sum = 0.0;
  StepStats nonzero_steps;
};

/// Pass 1 over V (not empty). lo and hi are what a left-to-right std::min / std::max fold from
/// v[0] gives: the first of equal extremes, which only the sign of a zero can tell apart (a NaN
/// in v[0] would stay; later NaNs are skipped). sum: sample i in lane i mod kLanes, then
/// lane_sum.
Extremes extremes(std::span<const double> v);

/// The steps above NOISE_FLOOR: those of pass 1 when its smallest nonzero step is above the
/// floor (the usual case: the floor is 1e-12 of the scale), else a pass of their own.
StepStats steps_above(std::span<const double> v, const Extremes& e, double noise_floor);

/// @}

/// @name The quantization step (estimate_lsb)
/// @{

inline constexpr double kTolerance = 0.1;  // |step − k·q| allowed, as a fraction of q
/// x + kRoundMagic − kRoundMagic rounds x to an integer (to nearest, ties to even, like
/// std::nearbyint in the default rounding mode) for 0 ≤ x < 2^51, without SSE4.1.
inline constexpr double kRoundMagic = 0x1.8p52;

/// What the LSB search takes from the extremes.
struct LsbBounds {
  double range = 0.0;
  double noise_floor = 0.0;  ///< steps below this are float rounding of equal codes
  bool usable = false;       ///< a positive, finite range
};

LsbBounds lsb_bounds(double lo, double hi);

inline bool is_multiple(double d, double q) {
  const double k = std::nearbyint(d / q);
  return k >= 1.0 && std::fabs(d - k * q) <= kTolerance * q;
}

/// The step into sample I if it is above the noise floor and not a multiple of Q, else 0.
inline double offending_step(std::span<const double> v, std::size_t i, double noise_floor,
                             double q) {
  const double d = std::fabs(v[i] - v[i - 1]);
  return d > noise_floor && !is_multiple(d, q) ? d : 0.0;
}

/// The vector test of the steps against a grid q: a step passes when k = round(d · (1/q)) ≥ 1
/// and |d − k·q| ≤ 0.09·q. A pass implies is_multiple: |d/q − k| ≤ 0.09 + 2^-13 (the rounding
/// of k·q for k < 2^40), so nearbyint(d / q) is the same k and |d − k·q| is within 10 % of q.
/// Steps that fail it go through is_multiple itself.
struct GridTest {
  double noise_floor, q, inv, tolerance;
};

/// The test for Q, or empty where it does not hold: every step is at most RANGE, so every
/// d·(1/q) < 2^40 (where kRoundMagic rounds exactly).
std::optional<GridTest> grid_test(double noise_floor, double q, double range);

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // see sampling_checks_internal.h
/// The steps D (|v[i] − v[i−1]|) above the noise floor that fail the test.
template <class D>
[[gnu::always_inline]] inline MaskOf<D> off_grid(const D& d, const GridTest& t) {
  const D k = (d * t.inv + kRoundMagic) - kRoundMagic;
  const MaskOf<D> fits = (k >= 1.0) & (vabs(d - k * t.q) <= t.tolerance);
  return (d > t.noise_floor) & ~fits;
}
#pragma GCC diagnostic pop

/// The first step above the noise floor that is not a multiple of Q (is_multiple), or 0.
/// Blocks whose steps all pass GridTest are skipped.
double first_offender(std::span<const double> v, double noise_floor, double q, double range);

/// estimate_lsb after its passes over the extremes and the steps, split where it needs the
/// first step of all that is off a grid q (a full scan): analyze_channel makes that scan
/// within its second pass. Usage: while (pending()) resume(first offender of *pending()).
class LsbSearch {
 public:
  LsbSearch(std::span<const double> values, const LsbBounds& bounds, const StepStats& stats);

  /// The grid whose first offender is needed next; empty once the search has ended.
  std::optional<double> pending() const { return pending_; }
  double range() const { return range_; }
  double noise_floor() const { return noise_floor_; }

  /// Goes on with the first offender of pending() (0 for none).
  void resume(double offender);

  std::optional<double> result() const { return result_; }

 private:
  /// Rounds until one needs a full scan (pending_) or the search fails.
  void advance();

  /// Least squares q = Σd / Σk over the small steps that fit the grid: averages the decimal
  /// printing error of each value down, so large steps are judged against an accurate q.
  double refine(double q) const;

  double range_, noise_floor_, q_;
  std::vector<double> small_;
  int round_ = 0;
  std::optional<double> pending_, result_;
};

/// @}

}  // namespace imunoise::pipeline::detail
