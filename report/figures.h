/// @file
/// @brief The report's figures, built from analysis results (pure: numbers in, Plot out):
/// Allan deviation per sensor with the fitted model, its terms and the IEEE-952 read-off
/// points; PSD per sensor with the model PSD; recorded drift against the predicted envelope
/// (pipeline/drift_series.h); the sampling intervals and gaps. Each Figure also gives the CSV of
/// exactly what it plots.
#pragma once

#include <string>
#include <vector>

#include "common/sensor_kind.h"
#include "io/allan_csv.h"
#include "io/psd_csv.h"
#include "models/noise_model.h"
#include "pipeline/drift_run.h"
#include "pipeline/drift_series.h"
#include "report/svg_plot.h"

namespace imunoise::report {

/// A plot with its name, caption and the CSV column names of its data (units included).
struct Figure {
  std::string name;     ///< e.g. "allan-gyro": the HTML id "fig-NAME", plots/NAME.svg/.csv
  std::string caption;  ///< what is plotted, one or two sentences
  Plot plot;
  std::vector<std::string> series_ids;  ///< per plot.series: its name in the CSV
  std::string x_column, y_column;       ///< e.g. "tau_s", "adev_rad_per_s"
  bool csv_intervals = true;  ///< the CSV has the _ci_low/_ci_high columns (false when the
                              ///< bars are only a drawing device, e.g. histogram stems)
};

/// The CSV of what FIGURE plots, one row per point: `series,X,Y,Y_ci_low,Y_ci_high` (empty
/// interval cells where a series has none; no interval columns when !csv_intervals), then one
/// `readoff: TEXT` row per labelled point.
/// Numbers are shortest round-trip decimals. FIGURE must name every series (series_ids as long
/// as plot.series; ContractViolation otherwise).
std::string figure_csv(const Figure& figure);

/// "allan-gyro" / "allan-accel": OADEV of the sensor's axes with interval bars; per axis the
/// fitted total model ADEV (solid) and each identified term (dashed: Q, N, B, K, R, GM,
/// sinusoids) from MODEL, over the measured τ range; the IEEE-952 slope read-offs marked where
/// the method reads them (Q at τ = √3 s, N at 1 s, B as 0.664·B at the ADEV minimum, K at
/// 3 s, R at √2 s; theory.md §4.2). Axes of the other sensor are ignored (an axis not named
/// gyro… counts as an accelerometer's).
Figure allan_figure(SensorKind kind, const std::vector<io::AllanAxis>& curves,
                    const models::NoiseModel& model);

/// "psd-gyro" / "psd-accel": the log-binned PSD of each axis (solid) and the model (dashed).
Figure psd_figure(SensorKind kind, const std::vector<io::PsdAxis>& spectra);

/// "drift-horizontal": each recorded segment's horizontal error (thin; thinned to ~120 points
/// evenly spaced in log time, which draw the same), their RMS (DRIFT.recorded_rms_m, when
/// not empty), and the predicted 1σ (DRMS) and 3σ envelopes, on log-log axes. Only the
/// horizontal parts of DRIFT are drawn.
Figure drift_figure(const pipeline::DriftSeries& drift,
                    const std::vector<pipeline::DriftSegment>& segments);

/// "drift-budget": the share [%] of each source (N, B, K, GM, R, alignment, heading;
/// ins::DriftBudgetTerm) in the predicted horizontal variance against time, stacked (each
/// source a band from the sum of those below it to that sum plus its own share; the top is
/// 100 %), on a log time axis over the times of BUDGET. Sources that are 0 throughout are
/// left out; the CSV holds each band's upper edge (the cumulative share).
Figure drift_budget_figure(const pipeline::DriftBudget& budget);

/// "sampling-intervals": histogram of the regular sample intervals [ms] as stems at the bin
/// centres (log count axis; empty bins left out), with the median marked. The three lists must
/// be equally long (ContractViolation otherwise).
Figure interval_figure(const std::vector<double>& bin_low_s, const std::vector<double>& bin_high_s,
                       const std::vector<std::int64_t>& counts, double median_interval_s);

/// "sampling-gaps": each gap's length against when it happened (hours since the first sample).
/// (The report shows a sentence instead when there are no gaps.) START_S and LENGTH_S must be
/// equally long (ContractViolation otherwise).
Figure gaps_figure(const std::vector<double>& start_s, const std::vector<double>& length_s,
                   double duration_s, std::int64_t gap_count);

}  // namespace imunoise::report
