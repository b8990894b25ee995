#include "analysis/selection_uncertainty.h"

#include <algorithm>
#include <cmath>

namespace imunoise::analysis {

PerTerm<SelectionWidening> selection_widened_intervals(
    std::span<const FitPoint> points, const FitResult& fit,
    const PerTerm<CoefficientInterval>& intervals, const PerTerm<double>& upper_bounds,
    int weight_iterations) {
  PerTerm<SelectionWidening> out{};
  // Squared log shifts below and above each identified term's estimate, summed over the
  // dropped terms; a term the held fit removes (s' = 0) sends its lower end to 0.
  PerTerm<double> down{}, up{};
  PerTerm<bool> to_zero{};
  for (NoiseTerm term : kNoiseTerms) out[term].interval = intervals[term];
  for (NoiseTerm dropped : kNoiseTerms) {
    const double bound = upper_bounds[dropped];
    if (fit.terms[dropped].identified || !std::isfinite(bound) || !(bound > 0.0)) continue;
    const FitResult held = refit_with_term_held(points, fit, dropped, bound, weight_iterations);
    for (NoiseTerm term : kNoiseTerms) {
      const TermFit& at_fit = fit.terms[term];
      if (!at_fit.identified || !(at_fit.value > 0.0)) continue;
      const double moved = held.terms[term].identified ? held.terms[term].value : 0.0;
      // Moves below 1e-6 relative are rounding of the re-solve, not a second model.
      if (std::fabs(moved / at_fit.value - 1.0) < 1e-6) continue;
      if (moved == 0.0) {
        to_zero[term] = true;
      } else {
        const double shift = std::log(moved / at_fit.value);
        (shift < 0.0 ? down : up)[term] += shift * shift;
      }
      SelectionWidening& w = out[term];
      w.moved_by += std::string(w.moved_by.empty() ? "" : ", ") + std::string(term_name(dropped));
    }
  }
  for (NoiseTerm term : kNoiseTerms) {
    const double s = fit.terms[term].value;
    if (out[term].moved_by.empty() || !(s > 0.0)) continue;
    CoefficientInterval& ci = out[term].interval;
    // The conditional half-widths in the log, each side, combined in quadrature with the
    // shifts (marginal = conditional + selection variance, see the header).
    if (to_zero[term]) {
      ci.low = 0.0;
    } else if (down[term] > 0.0) {
      const double half = ci.low > 0.0 && ci.low < s ? std::log(s / ci.low) : 0.0;
      ci.low = s * std::exp(-std::sqrt(half * half + down[term]));
    }
    if (up[term] > 0.0) {
      const double half = ci.high > s ? std::log(ci.high / s) : 0.0;
      ci.high = s * std::exp(std::sqrt(half * half + up[term]));
    }
  }
  return out;
}

}  // namespace imunoise::analysis
