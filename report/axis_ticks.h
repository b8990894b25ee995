/// @file
/// @brief Axis ticks for the SVG plots: "nice" 1-2-5 linear ticks and decade ticks on log10
/// axes, with their label texts. Locale-independent and deterministic (std::to_chars).
#pragma once

#include <string>
#include <vector>

namespace imunoise::report {

/// One tick mark. Major ticks get a grid line and (unless text is empty) a label; minor ticks
/// get a short mark and a lighter grid line.
struct Tick {
  double value = 0.0;
  std::string text;  ///< label; "" = unlabelled. Log decades read "10^k" (k an integer).
  bool major = true;
};

/// Linear ticks at multiples of a 1-2-5 step (1, 2 or 5 × 10^e), the step chosen so that the
/// ticks enclosing [LO, HI] number closest to TARGET_COUNT (ties: the smaller step). The
/// first tick is ≤ LO and the last ≥ HI, so [front, back] is the autoscaled axis range.
/// Labels have just the digits they need ("0", "0.2", "1", "12.5"); values of magnitude
/// ≥ 1e6 or < 1e-3 use the scientific form ("1e-06", "2.5e+07"). A tick at zero is exactly 0.
/// LO > HI are swapped; an empty range (LO == HI, or a width below 1e-12 of the magnitude)
/// is widened to ±10 % of the value (±1 around 0). Non-finite bounds give no ticks.
std::vector<Tick> linear_ticks(double lo, double hi, int target_count = 6);

/// Log10 ticks over the whole decades enclosing [LO, HI] (both > 0, else no ticks): majors at
/// 10^k labelled "10^k", minors at 2..9 × 10^k (unlabelled, only when the span is ≤ 12
/// decades). Over more than 12 decades only every n-th decade (n = ⌈span/10⌉, multiples of n)
/// is a labelled major; the other decades become unlabelled minor ticks, or are left out when
/// the span exceeds 60 decades. A single decade value (LO == HI == 10^k) spans 10^(k-1)..10^(k+1).
std::vector<Tick> log10_ticks(double lo, double hi);

/// The decade 10^⌊log10 V⌋ at or below V (exact; clamped to 1e-307 … 1e308, NaN → 1e-307).
double decade_floor(double v);
/// The decade 10^⌈log10 V⌉ at or above V (exact; clamped to 1e-307 … 1e308, NaN → 1e-307).
double decade_ceil(double v);

}  // namespace imunoise::report
