/// @file
/// @brief The four result files of `imunoise drift`, each written and read back here over one
/// typed struct (pipeline/drift_series.h, pipeline/drift_run.h): drift_envelope.csv
/// (DriftSeries), drift_segments.csv (DriftSegment per segment), drift_summary.json
/// (DriftSummary) and drift_budget.csv (DriftBudget). Files hold human units where their column or
/// key says so (deg); the structs are SI. Writes are atomic (io/atomic_output.h). Every reader
/// checks the columns or keys it needs and reports a bad file as InputError "FILE[:LINE]: problem".
#pragma once

#include <string>
#include <vector>

#include "pipeline/drift_run.h"
#include "pipeline/drift_series.h"

namespace imunoise::io {

/// @name drift_envelope.csv
/// `time_s`, the predicted 1σ (`predicted_north_sigma_m`, `predicted_east_sigma_m`,
/// `predicted_horizontal_drms_m`, `predicted_horizontal_velocity_drms_m_per_s`,
/// `predicted_roll_sigma_deg`, `predicted_pitch_sigma_deg`, `predicted_heading_sigma_deg`),
/// then, when the series has them, `actual_rms_horizontal_error_m` (recorded_rms_m) and
/// `mc_radial_p50_m`, `mc_radial_p68_m`, `mc_radial_p95_m`, `mc_radial_rms_m`; one row per
/// time, shortest round-trip numbers.
/// @{

/// The text of drift_envelope.csv. @throws ContractViolation when a non-empty vector of SERIES
/// is not as long as time_s, or a predicted one is empty.
std::string format_drift_envelope_csv(const pipeline::DriftSeries& series);
void write_drift_envelope_csv(const std::string& path, const pipeline::DriftSeries& series);

/// Reads PATH back. The time and predicted columns are required, every cell filled; the
/// recorded and the Monte Carlo columns are optional groups (one column of a group requires
/// the others), left empty when a row lacks a value. predicted_attitude_sigma_rad is computed
/// from the three angles in deg as the file holds them.
pipeline::DriftSeries read_drift_envelope_csv(const std::string& path);
/// @}

/// @name drift_segments.csv
/// `segment` (0, 1, …), `start_s`, `time_s`, `north_error_m`, `east_error_m`,
/// `horizontal_error_m` (|north, east|, not read back), `horizontal_velocity_error_m_per_s`,
/// `attitude_error_north_deg`, `attitude_error_east_deg`, `attitude_error_down_deg`; one row
/// per segment and time, segment by segment.
/// @{

/// The text of drift_segments.csv. @throws ContractViolation when the vectors of a segment
/// differ in length.
std::string format_drift_segments_csv(const std::vector<pipeline::DriftSegment>& segments);
void write_drift_segments_csv(const std::string& path,
                              const std::vector<pipeline::DriftSegment>& segments);

/// Reads PATH back: one DriftSegment per run of rows with the same segment number, in file
/// order. Every column but horizontal_error_m is required, every cell filled.
std::vector<pipeline::DriftSegment> read_drift_segments_csv(const std::string& path);
/// @}

/// @name drift_budget.csv
/// Columns `time_s`, `report_time` (1 at a report time, else 0), then per source
/// (ins::DriftBudgetTerm order) `<name>_variance_m2` (white_noise, bias_instability,
/// random_walk, gauss_markov, ramp, alignment, heading), then
/// `predicted_horizontal_variance_m2`; one row per time of pipeline::DriftBudget (the report
/// times and a log-spaced grid).
/// @{

/// The text of drift_budget.csv. @throws ContractViolation when the vectors differ in length.
std::string format_drift_budget_csv(const pipeline::DriftBudget& budget);
void write_drift_budget_csv(const std::string& path, const pipeline::DriftBudget& budget);
/// Reads PATH back; every column required, every cell filled, report_time 0 or 1.
pipeline::DriftBudget read_drift_budget_csv(const std::string& path);
/// @}

/// @name drift_summary.json
/// An object with "recording", "model", "location" {latitude_deg, longitude_deg, height_m,
/// given}, "protocol" {align_s, navigation_s, warmup_s, segments, vertical_channel, gyro_bias,
/// heading, bias_instability_as_gm, bias_states (optional when read)}, "motion_check" {stationary,
/// reason, forced, max_gyro_std_ratio, max_accel_std_ratio, max_force_deviation_m_per_s2,
/// max_tilt_change_deg, max_rotation_deg_per_s}, "consistency" (one object per report time: time_s,
/// predicted_north_sigma_m, predicted_east_sigma_m, predicted_horizontal_drms_m,
/// actual_rms_horizontal_error_m, mean_nees, mean_nees_band_95 [2], nees_inside_band,
/// mean_nees_joint_band_95 [2], nees_inside_joint_band,
/// coverage_1_2_3_sigma [3], expected_coverage_1_2_3_sigma [3], rms_ratio,
/// rms_ratio_ci_95 [2], and with the Monte Carlo monte_carlo_radial_rms_m and
/// monte_carlo_radial_p95_m), when it ran, "monte_carlo" {runs, seed}, and with the
/// split-sample check "holdout" {fitted_on, judged_on, segments, consistency (as above,
/// without the Monte Carlo keys)}. A non-finite number
/// is written as null and read back as NaN.
/// @{

/// The text of drift_summary.json (2-space indented, keys sorted, newline-terminated).
std::string format_drift_summary_json(const pipeline::DriftSummary& summary);
void write_drift_summary_json(const std::string& path, const pipeline::DriftSummary& summary);

/// Reads PATH back. Every key above is required (the Monte Carlo ones only together);
/// InputError "PATH: KEY: problem" names the first one missing or of the wrong type.
pipeline::DriftSummary read_drift_summary_json(const std::string& path);
/// @}

}  // namespace imunoise::io
