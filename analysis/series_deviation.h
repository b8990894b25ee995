/// @file
/// @brief One deviation curve of one series (`imunoise allan`): rate or phase samples →
/// phase → the averaging factors of a τ grid → the curve with its confidence intervals.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "analysis/deviation.h"
#include "analysis/tau_grid.h"

namespace imunoise::analysis {

/// What the samples of a series are.
enum class SeriesKind {
  kRate,   ///< rate ("frequency") samples y, e.g. rad/s
  kPhase,  ///< their integral x (phase), e.g. rad
};

/// Fewest values a series of KIND needs: 1 rate sample, 2 phase samples.
std::size_t min_series_values(SeriesKind kind);

/// The curve of OPTIONS.type of VALUES (at least min_series_values(KIND)) sampled every
/// TAU0_S, at the averaging factors GRID gives for it. The phase is detrended_phase(VALUES),
/// or phase_from_rate(VALUES, TAU0_S) for rate data (SI inside: the phase of rate data is in
/// input unit·s).
/// @throws AnalysisError "WHERE: MESSAGE" when the series is too short for the grid
/// (averaging_factors' MESSAGE), and as compute_deviation; ContractViolation for fewer than
/// min_series_values(KIND) values.
DeviationCurve series_deviation(std::span<const double> values, SeriesKind kind, double tau0_s,
                                const TauGridSpec& grid, const DeviationOptions& options,
                                std::string_view where);

}  // namespace imunoise::analysis
