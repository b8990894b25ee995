/// @file
/// @brief Time-stamp gaps in a recording and the two ways `imunoise analyze` can go on
/// despite them (the third, the default, is to refuse): split the record into its gap-free
/// pieces (whose statistics are then pooled, analysis::compute_pooled_deviation and
/// analysis::pooled_welch_psd), or fill each gap by linear interpolation. Pure computation
/// over time stamps and sample values; the caller words the errors with the file name.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/sampling_gap.h"
#include "pipeline/recording.h"

namespace imunoise::pipeline {

/// What to do with time-stamp gaps (`analyze --gaps`).
enum class GapPolicy {
  refuse,       ///< stop with an error naming the gaps (default: the statistics assume a
                ///< uniform grid, theory.md §2, so a gap silently biases every τ across it)
  split,        ///< analyse the gap-free pieces and pool them
  interpolate,  ///< fill each gap linearly with the samples it lacks
};

/// How the messages and the data-quality note of this file name the gap-policy setting, which
/// the policy follows ("gap policy split: …"). A caller that offers the setting to its user
/// under another name passes that name instead: the CLI passes its flag, "--gaps".
inline constexpr std::string_view kGapPolicySetting = "gap policy";

/// Parses "refuse" / "split" / "interpolate"; throws InputError "SETTING: expected refuse,
/// split or interpolate, got 'TEXT'" otherwise.
GapPolicy parse_gap_policy(std::string_view text, std::string_view setting = kGapPolicySetting);

/// One gap: an interval t[after] − t[after − 1] longer than gap_factor × the nominal period.
struct TimeGap {
  std::size_t after = 0;     ///< index of the first sample after the gap (≥ 1)
  double start_s = 0.0;      ///< time of the sample before the gap [s]
  double length_s = 0.0;     ///< the interval [s]
  std::int64_t missing = 0;  ///< samples it lacks: missing_samples_in_gap (saturating)
};

/// Every gap of TIME_S (not only the first pipeline::kMaxListedGaps the sampling report lists),
/// with the criterion of pipeline::analyze_timing: interval > gap_factor × period_s. Intervals
/// ≤ 0 (duplicate or disordered stamps) are not gaps. Throws ContractViolation when period_s ≤ 0
/// or is not finite.
std::vector<TimeGap> find_time_gaps(std::span<const double> time_s, double period_s,
                                    double gap_factor = kGapFactor);

/// A half-open range [begin, end) of sample indices.
struct SampleRange {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};

/// The gap-free pieces of an N-sample record.
struct GapSplit {
  std::vector<SampleRange> pieces;  ///< kept pieces, in time order
  std::size_t dropped_pieces = 0;   ///< pieces shorter than the minimum
  std::size_t dropped_samples = 0;  ///< samples in them
};

/// Pieces shorter than this are dropped by split_at_gaps in `analyze` (a piece must carry a
/// few octaves of τ of its own to add information rather than edge effects).
inline constexpr std::size_t kMinPieceSamples = 100;

/// Cuts [0, n) at every gap (GAPS in time order, `after` increasing and < n, else
/// ContractViolation) and keeps the pieces with at least MIN_PIECE samples.
GapSplit split_at_gaps(std::size_t n, std::span<const TimeGap> gaps, std::size_t min_piece);

/// Largest gap interpolate_gaps may fill, in missing samples, for an N-sample record:
/// min(1000, max(1, ⌊n/100⌋)). Beyond 1 % of the record (or 1000 samples) the straight line
/// is a visible fraction of the data and biases the long-τ end; split is the honest choice.
std::int64_t max_interpolated_gap(std::size_t n);

/// VALUES with every gap filled: gap g gets g.missing samples x_{a−1} + (x_a − x_{a−1})·j/(k+1),
/// j = 1…k, k = g.missing, between its neighbours a − 1 and a = g.after. Output length
/// n + Σ missing. GAPS as returned by find_time_gaps (in time order inside VALUES, else
/// ContractViolation).
std::vector<double> interpolate_gaps(std::span<const double> values, std::span<const TimeGap> gaps);

/// How the samples of every channel of a recording reach the analysis under a gap policy.
struct GapPlan {
  GapPolicy policy = GapPolicy::refuse;
  std::vector<TimeGap> gaps;        ///< every gap (split, interpolate)
  std::vector<SampleRange> pieces;  ///< split: kept pieces; else empty
  std::int64_t samples = 0;         ///< samples analysed per channel
  std::string note;                 ///< data-quality line ("" without gaps)
};

/// Applies POLICY to the gaps of RECORDING (SOURCE names it in messages): refuses
/// (InputError gap_refusal_message), or plans the split or the interpolation and words the
/// data-quality line (BOOTSTRAP: the note says the bootstrap of a split record is
/// approximate). Throws AnalysisError when a split leaves no piece of kMinPieceSamples,
/// InputError when a gap is too long to interpolate. The note and the messages name the
/// policy as SETTING followed by its name ("--gaps split: 3 time-stamp gap(s); …").
GapPlan plan_gaps(const Recording& recording, const std::string& source, GapPolicy policy,
                  bool bootstrap, std::string_view setting = kGapPolicySetting);

/// The one-line refusal of a recording with time-stamp gaps under GapPolicy::refuse: SOURCE
/// (with the line of the first gap when known), the number of gaps, where the first is, the
/// longest, the samples missing, and the two policies that go on (named as SETTING split and
/// SETTING interpolate). Empty when there is no gap.
std::string gap_refusal_message(const std::string& source, const TimingReport& timing,
                                std::string_view setting = kGapPolicySetting);

}  // namespace imunoise::pipeline
