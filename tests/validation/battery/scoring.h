/// @file
/// @brief Scoring of one fitted model (model.yaml of `imunoise analyze`, read with
/// io/noise_model_yaml.h) against the truth of its battery case, and the summary tables of
/// many scored recordings (docs/validation.md "Scoring" defines every figure).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "battery/battery_cases.h"
#include "models/noise_model.h"

namespace imunoise::battery {

/// The coefficient classes scored, in table order.
enum class Coefficient {
  quantization,
  white_noise,
  bias_instability,
  random_walk,
  ramp,
  gm_sigma,
  gm_tau_c,
  sinusoid_amplitude
};
inline constexpr std::array<Coefficient, 8> kCoefficients = {Coefficient::quantization,
                                                             Coefficient::white_noise,
                                                             Coefficient::bias_instability,
                                                             Coefficient::random_walk,
                                                             Coefficient::ramp,
                                                             Coefficient::gm_sigma,
                                                             Coefficient::gm_tau_c,
                                                             Coefficient::sinusoid_amplitude};
/// "Q", "N", "B", "K", "R", "GM sigma", "GM T_c", "sine A".
const char* coefficient_label(Coefficient c);
/// "quantization", …, "gm_sigma", "gm_tau_c", "sinusoid_amplitude" (the CSV `term` column).
const char* coefficient_key(Coefficient c);

/// One scored coefficient of one channel.
struct ScoreRow {
  std::string channel;
  Coefficient term = Coefficient::white_noise;
  double truth = 0.0;              ///< 0 = the truth lacks the term
  double truth_as_recorded = 0.0;  ///< see ChannelTruth::white_noise_as_recorded
  double estimate = 0.0;
  double ci_low = 0.0, ci_high = 0.0;
  bool has_interval = false;  ///< model.yaml gives an interval for this coefficient
  bool identified = false;
  bool covered = false;          ///< truth > 0 and ci_low ≤ truth ≤ ci_high
  double readoff = 0.0;          ///< IEEE-952 slope read-off from model.yaml (0 = not found)
  double frequency_hz = 0.0;     ///< sinusoids: the truth's f; GM: the truth's T_c
  double line_snr = 0.0;         ///< sinusoids: TruthLine::snr
  double k_share_t10 = 0.0;      ///< K rows: share of K²τ/3 in the truth AVAR at τ = T/10
  std::optional<bool> psd_pass;  ///< the channel's PSD cross-check verdict
};

/// Spurious terms of a channel beyond the rows: GM terms and lines the truth lacks.
struct ChannelExtras {
  std::string channel;
  int false_gm = 0;     ///< fitted GM terms matched to no truth GM
  int false_lines = 0;  ///< fitted sinusoids matched to no truth line
  bool truth_has_gm = false, truth_has_lines = false;
};

/// Scores MODEL against the truth of CASE: one row per channel and coefficient class the truth
/// has or the model reports (power-law terms always; one GM pair per truth GM; one row per
/// truth line). GM terms match by T_c within a factor 3, lines by frequency within
/// max(2 %, 2/T). Channels missing from the model score as not identified.
std::vector<ScoreRow> score_model(const BatteryCase& c, const models::NoiseModel& model,
                                  std::vector<ChannelExtras>& extras);

/// The rows of a recording whose analysis failed: every truth term not identified, not covered.
std::vector<ScoreRow> score_failure(const BatteryCase& c, std::vector<ChannelExtras>& extras);

/// Which phenomena the model's findings name (data_quality lines and each axis's fit and PSD
/// notes, matched by the case-insensitive patterns of docs/validation.md).
std::array<bool, kPhenomena.size()> findings_present(const models::NoiseModel& model);

/// One analysed recording with its rows.
struct RecordingResult {
  std::string class_name, grade;
  std::uint64_t seed = 0;
  double rate_hz = 0.0, duration_s = 0.0;
  double generate_s = 0.0, write_s = 0.0, analyze_s = 0.0;
  int exit_code = 0;
  std::vector<Phenomenon> phenomena;
  std::array<bool, kPhenomena.size()> findings{};
  std::vector<std::string> finding_lines;
  std::vector<ScoreRow> rows;
  std::vector<ChannelExtras> extras;
};

/// The markdown summary tables of RESULTS (docs/validation.md "Scoring"). TITLE heads it.
std::string summary_markdown(const std::vector<RecordingResult>& results, const std::string& title);

/// The acceptance targets of issue 20 that the battery measures (coverage 95 ± 5 % per class,
/// false terms ≤ 2 %, K identified ≥ 80 %, PSD check ≥ 95 %, lines ≥ 90 % found and ≤ 1 false
/// per 10 channels, findings on every case with the phenomenon and none without, median
/// errors N ≤ 0.5 %, B ≤ 5 %, K ≤ 15 % and below the read-off's) as a markdown table;
/// ALL_MET tells whether every one holds.
std::string acceptance_markdown(const std::vector<RecordingResult>& results, bool& all_met);

/// The per-row CSV (header + one line per row of every result).
std::string rows_csv(const std::vector<RecordingResult>& results);
/// The per-recording CSV (times, exit codes, findings).
std::string recordings_csv(const std::vector<RecordingResult>& results);

}  // namespace imunoise::battery
