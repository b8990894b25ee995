/// @file
/// @brief One-dimensional golden-section minimization: the 1-D search of the GM correlation
/// times (analysis/noise_fit) and of a spectral line's frequency (analysis/spectral_lines).
#pragma once

#include <algorithm>
#include <cmath>

namespace imunoise::analysis {

/// Minimizes F on [LO, HI] by golden-section search until the bracket is narrower than
/// TOLERANCE (at most 200 steps); returns the best abscissa evaluated, the bracket ends
/// included (the minimum may sit on the boundary). F must be unimodal on [LO, HI].
template <class F>
double golden_section_minimum(F&& f, double lo, double hi, double tolerance) {
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = lo, b = hi;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 200 && b - a > tolerance; ++i) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - ratio * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + ratio * (b - a);
      f2 = f(x2);
    }
  }
  double best = f1 <= f2 ? x1 : x2;
  double best_value = std::min(f1, f2);
  for (double edge : {lo, hi}) {
    const double value = f(edge);
    if (value < best_value) {
      best_value = value;
      best = edge;
    }
  }
  return best;
}

}  // namespace imunoise::analysis
