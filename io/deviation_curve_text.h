/// @file
/// @brief One deviation curve of one series as `imunoise allan` prints it: a JSON object
/// (keys carry units) or a text table with a '#' header naming the statistic, the source, τ0
/// and the EDF model of the confidence interval.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "analysis/deviation.h"

namespace imunoise::io {

/// What the output states besides the curve.
struct SeriesCurveInfo {
  std::string data;                     ///< what the values are: "rate" or "phase"
  std::string source;                   ///< the file read
  std::string column;                   ///< the column (or channel's source column) read
  std::size_t n_samples = 0;            ///< values in the series
  std::string tau0_source;              ///< where τ0 came from, in words
  std::int64_t non_finite_dropped = 0;  ///< NaN/Inf values dropped from the series
  std::optional<int> alpha;             ///< the noise type fixed for the EDF; none = per τ
  bool bias_corrected = false;          ///< the SP 1065 bias removal was asked for
};

/// The JSON object: type, data, tau0_s, n_samples, confidence, tau0_source, source, column,
/// n_phase, non_finite_dropped, value_unit ("input unit", or "input unit * s" for TDEV and
/// TTOTDEV), bias_corrected (asked for and applicable to the type), and points (m, tau_s,
/// value, n_terms, alpha, edf, ci_low, ci_high).
nlohmann::ordered_json series_curve_json(const analysis::DeviationCurve& curve,
                                         const SeriesCurveInfo& info);

/// The text table: two '#' lines (statistic, source, column, data, τ0 and its source, counts;
/// the interval's level and EDF model), a '#' line with the NaN/Inf count when some were
/// dropped, the column line, and one line per point (m, tau_s, n_terms, alpha, edf, ci_low,
/// value, ci_high).
std::string series_curve_table(const analysis::DeviationCurve& curve, const SeriesCurveInfo& info);

}  // namespace imunoise::io
