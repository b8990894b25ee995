/// @file
/// @brief Model-selection uncertainty in the intervals of the identified terms (issue 20
/// item 5): when the fit drops a term the data cannot exclude (K, R, Q), the other terms'
/// intervals are conditional on that term being zero; they are widened by how far each term
/// moves when the dropped one is held at its upper bound.
#pragma once

#include <span>
#include <string>

#include "analysis/noise_fit.h"

namespace imunoise::analysis {

/// How one identified term's interval was widened.
struct SelectionWidening {
  CoefficientInterval interval;  ///< the projected interval (contains the given one)
  /// The dropped terms whose bound moved the interval, e.g. "random_walk"; empty: unchanged.
  std::string moved_by;
};

/// INTERVALS (of FIT's identified power-law terms, conditional on FIT's structure) widened by
/// the terms FIT did not identify: for each such term t with a finite UPPER_BOUNDS[t], the fit
/// with t held at its bound (refit_with_term_held()) moves each identified term s to s'. The
/// bound is the χ²₁(95 %) deviance rise, i.e. about 1.96 standard errors of t away from 0, so
/// ln(s'/s) is 1.96 × the part of s's log-scale error that t's uncertainty adds; it is added in
/// quadrature to the conditional half-width of the log on its side (the marginal variance of
/// s in the model with t free is the conditional one plus (∂s/∂t)²·Var t), summed over the
/// dropped terms (taken as independent), and only on the side t's sign allows (t ≥ 0). An s
/// that the held fit drops (s' = 0) gets a lower end of 0. Terms not identified are returned
/// as given (moved_by empty). Measured effect: docs/validation.md.
PerTerm<SelectionWidening> selection_widened_intervals(
    std::span<const FitPoint> points, const FitResult& fit,
    const PerTerm<CoefficientInterval>& intervals, const PerTerm<double>& upper_bounds,
    int weight_iterations = FitOptions{}.weight_iterations);

}  // namespace imunoise::analysis
