/// @file
/// @brief What each finding of an analysis means and what to do about it: the one table of
/// finding kinds (how a finding's text is recognised, its cause, its remedy naming the command
/// or flag that addresses it), and the findings of a fitted model explained with it — the
/// data_quality lines, the failed PSD cross-checks and each part of every fit note. A text no
/// kind recognises (a finding added after this table) gets a generic but honest cause and
/// remedy, never an error. Pure: a model in, explanations out.
///
/// To add a kind: append a row to kFindingKinds in finding_remedies.cpp (its marker is a piece
/// of text every finding of the kind contains and no other does), and add the finding's
/// producer to tests/report/finding_remedies_test.cpp, which checks that every finding the
/// pipeline emits is recognised.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "models/noise_model.h"

namespace imunoise::report {

/// Where a finding came from.
enum class FindingSource { data_quality, psd_check, fit_note, drift };

/// What a remedy may use besides the finding's own text.
struct FindingContext {
  std::string_view text;                       ///< the finding as the pipeline wrote it
  const models::NoiseModel* model = nullptr;   ///< the fitted model, when there is one
  const models::AxisModel* axis = nullptr;     ///< the axis of a PSD check or fit note
  std::string_view model_path = "model.yaml";  ///< how commands refer to model.yaml
};

/// One kind of finding. The first row whose marker the text contains is its kind.
struct FindingKind {
  std::string_view id;      ///< e.g. "time_gaps"
  FindingSource source;     ///< which producer writes it
  std::string_view marker;  ///< text every finding of this kind contains
  std::string_view cause;   ///< why it happens
  /// What to do: the command or flag that addresses it (a sentence).
  std::string (*remedy)(const FindingContext& context);
};

/// Every kind this version knows, in matching order.
std::span<const FindingKind> finding_kinds();

/// The kind whose marker TEXT contains (first in table order), nullptr when none does.
const FindingKind* classify_finding(std::string_view text);

/// The kind id of a finding no row recognises.
inline constexpr std::string_view kUnknownFindingKind = "unknown";

/// One finding with its cause and remedy.
struct ExplainedFinding {
  std::string where;  ///< "recording", an axis name (gyro_x …) or "drift"
  std::string text;   ///< the finding as written (one fit-note part)
  std::string kind;   ///< FindingKind::id, or kUnknownFindingKind
  std::string cause;
  std::string remedy;
};

/// TEXT explained as a finding of WHERE with CONTEXT (a generic cause and remedy when no kind
/// recognises it).
ExplainedFinding explain_finding(std::string where, const FindingContext& context);

/// Every finding of MODEL: its data_quality lines ("recording"), then per axis its failed PSD
/// cross-check and each "; "-separated part of its fit note, each explained. MODEL_PATH is how
/// the remedies' commands name model.yaml.
std::vector<ExplainedFinding> explain_model_findings(const models::NoiseModel& model,
                                                     std::string_view model_path);

/// Why TERM of AXIS was not identified and what recording would show it (theory.md §4.1): the
/// τ range where the term at its upper bound would exceed the rest of the fitted model,
/// compared with the fitted τ range and the sample period; always a sentence. DURATION_S and
/// SAMPLE_RATE_HZ are the record's (0 = unknown).
std::string unidentified_term_remedy(const models::AxisModel& axis, NoiseTerm term,
                                     double duration_s, double sample_rate_hz);

/// The record length [s] at which the fit would reach the τ where TERM of AXIS, at its upper
/// bound, equals the rest of the model; nullopt when no length shows it (the bound stays below
/// the rest everywhere, the term shows only below the fitted range, or there is no bound).
std::optional<double> duration_to_show_term(const models::AxisModel& axis, NoiseTerm term,
                                            double duration_s);

/// The term a fit-note part names first ("random_walk dropped: …"), nullopt for a
/// Gauss–Markov or sinusoid column or any other text.
std::optional<NoiseTerm> leading_term(std::string_view note);

}  // namespace imunoise::report
