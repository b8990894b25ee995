/// @file
/// @brief How long to record (`imunoise plan`): for a noise model of each axis, the expected
/// precision of every term that `imunoise analyze` would report from a recording of a given
/// duration at a given rate, and the shortest duration that identifies each term and that
/// brings each term's interval to a target relative half-width.
///
/// The expected interval of a duration T is made the way analyze makes its default interval
/// (pipeline/axis_analysis, pipeline/bootstrap): the OAVAR τ grid of T at the rate, the
/// model's AVAR at each τ (analysis/noise_terms.h, theory.md §4.1), the EDF from the
/// dominant term (apply_model_noise_type), the weighted NNLS fit with its model selection on
/// those noise-free points (a term the selection keeps there is "identified": its expected
/// deviance drop exceeds the fit's penalty), then the fit's own interval draws — OAVAR vectors
/// drawn from their covariance across τ under the fitted model and refitted with the same
/// structure (ReplicateSource::variance_distribution, 200 draws, the analysis's seed), each
/// set's intervals widened by model-selection uncertainty as analyze widens its own (the
/// terms the fit drops held at their profile upper bounds: selection_upper_bounds in
/// pipeline/axis_analysis.h, analysis/selection_uncertainty.h). The relative half-width of a
/// term is (high − low)/(2·estimate) of that interval, the median over 5 sets of 200 draws
/// (the first set is the analysis's own).
/// Pure computation: no files, no flags (messages name the caller's setting).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/noise_fit.h"
#include "analysis/tau_grid.h"
#include "common/noise_coefficients.h"
#include "common/noise_term.h"

namespace imunoise::pipeline {

/// The analysis settings the plan replicates; the defaults are `imunoise analyze`'s.
struct RecordingPlanOptions {
  double confidence = 0.95;  ///< level of the intervals
  analysis::TauGridSpec grid = analysis::parse_tau_grid("log:10");
  analysis::FitOptions fit;      ///< fit settings (tau_min_s 0 = automatic low-pass check)
  int interval_draws = 200;      ///< draws of the OAVAR vector per interval, as analyze (≥ 2)
  int interval_draw_sets = 5;    ///< sets of draws per evaluation; the half-width is the median
  std::uint64_t seed = 1;        ///< master seed, mixed with the axis index as analyze does
  unsigned threads = 1;          ///< worker threads across (axis, duration) evaluations
  double min_duration_s = 60.0;  ///< shortest duration searched [s]
  double max_duration_s = 30.0 * 86400.0;  ///< longest duration searched [s]
};

/// The expected outcome for one term of one axis at one duration.
struct TermPrecision {
  bool present = false;     ///< the model has the term (coefficient > 0)
  bool identified = false;  ///< the fit of the expected OAVAR keeps it
  /// (ci_high − ci_low)/(2·estimate) of the expected interval [fraction]; +∞ when the term
  /// is not identified or has no interval.
  double relative_halfwidth = std::numeric_limits<double>::infinity();
};

/// A target: the term's relative half-width at most RELATIVE_HALFWIDTH.
struct PlanTarget {
  NoiseTerm term = NoiseTerm::random_walk;
  double relative_halfwidth = 0.2;  ///< [fraction], in (0, 10]
};

/// Parses "K:20%,B:10%" (term symbols Q N B K R; a percentage, or a fraction without '%';
/// each term at most once). Empty text gives no target.
/// @throws InputError naming SETTING and the offending item.
std::vector<PlanTarget> parse_plan_targets(std::string_view text, std::string_view setting);

/// One axis to plan: its name (gyro_x …) and its model (SI).
struct PlanAxis {
  std::string name;
  NoiseCoefficients model;
};

/// The expected precision of every term of MODEL for a recording of DURATION_S at RATE_HZ.
/// AXIS_INDEX (0 … 5) mixes into the draws' seed as in the analysis. A record too short for
/// any fit gives nothing identified.
/// @throws ContractViolation when the rate or duration is not > 0 or the options are invalid.
PerTerm<TermPrecision> expected_precision(const NoiseCoefficients& model, double rate_hz,
                                          double duration_s, int axis_index,
                                          const RecordingPlanOptions& options);

/// The plan of one axis.
struct AxisPlan {
  std::string name;
  std::vector<PerTerm<TermPrecision>> table;  ///< per RecordingPlan::durations_s
  /// Shortest duration from which the term is identified (at every longer table duration) [s];
  /// +∞ when not within the searched range; NaN when the model lacks the term.
  PerTerm<double> identify_duration_s;
  /// Shortest duration from which the term is identified with a relative half-width at most
  /// its target (at every longer table duration) [s]; +∞ when not within the range; NaN when there
  /// is no target for the term or the model lacks it.
  PerTerm<double> target_duration_s;
};

/// The whole plan.
struct RecordingPlan {
  double rate_hz = 0.0;
  std::vector<double> durations_s;  ///< the table's durations [s], ascending
  std::vector<PlanTarget> targets;
  std::vector<AxisPlan> axes;
  /// Longest of the axes' target durations: the shortest recording meeting every target [s];
  /// +∞ when one is beyond the range; NaN without targets.
  double all_targets_duration_s = std::numeric_limits<double>::quiet_NaN();
};

/// Plans AXES at RATE_HZ for TARGETS. The table holds the durations 1, 2, 5, 10, 20, 30 min,
/// 1, 2, 3, 4, 6, 8, 12, 16 h, 1, 1.5, 2, 3, 4, 5, 7, 10, 14, 20, 30 … days inside the
/// searched range. A required duration is found in two steps: the table duration above the
/// longest one where the condition fails, then 5 bisection steps in ln T inside that bracket
/// (to ≈ 3 %). Both steps are monotone in the target — a tighter target fails wherever a
/// looser one fails, and the evaluations are deterministic — so a tighter target never gives a
/// shorter duration.
/// @throws InputError (naming TARGET_SETTING) when a target names a term no axis has.
RecordingPlan plan_recording(std::span<const PlanAxis> axes, double rate_hz,
                             std::span<const PlanTarget> targets,
                             const RecordingPlanOptions& options,
                             std::string_view target_setting = "targets");

/// The expected precision of every axis at one duration (the inverse of the plan): a plan
/// whose table has the single duration DURATION_S and no required durations.
RecordingPlan precision_at(std::span<const PlanAxis> axes, double rate_hz, double duration_s,
                           std::span<const PlanTarget> targets,
                           const RecordingPlanOptions& options);

/// Whether PRECISION meets TARGET: identified and half-width ≤ the target.
bool meets_target(const TermPrecision& precision, const PlanTarget& target);

}  // namespace imunoise::pipeline
