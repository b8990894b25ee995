/// @file
/// @brief The finding kinds with their causes and remedies (see finding_remedies.h).
#include "report/finding_remedies.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "analysis/noise_terms.h"
#include "common/number_text.h"
#include "models/datasheet_units.h"
#include "pipeline/axis_analysis.h"

namespace imunoise::report {

namespace {

std::string text(std::string_view s) { return std::string(s); }

std::string term_remedy(const FindingContext& c) {
  const std::optional<NoiseTerm> term = leading_term(c.text);
  if (!term || !c.axis) {
    return "a Gauss-Markov or sinusoid column the data do not support is simply left out; "
           "nothing to do (analyze --gauss-markov / --sinusoid-hz F force them in)";
  }
  return unidentified_term_remedy(*c.axis, *term, c.model ? c.model->duration_s : 0.0,
                                  c.model ? c.model->sample_rate_hz : 0.0);
}

std::string gaps_remedy(const FindingContext&) {
  return "`imunoise check REC` lists every gap; record again with a larger driver buffer, or "
         "analyze with --gaps split (pool the gap-free pieces) or --gaps interpolate (short "
         "gaps only)";
}
std::string stamp_order_remedy(const FindingContext&) {
  return "sort the rows by time or keep one sensor's stream (`imunoise check REC` names the "
         "first such line), or analyze with --rate HZ to use the nominal rate instead of the "
         "stamps";
}
std::string duplicate_remedy(const FindingContext&) {
  return "drop repeated samples if the logger wrote them twice; if only the stamps are "
         "coarse, analyze with --rate HZ (`imunoise check REC` shows the spacing)";
}
std::string quantized_stamps_remedy(const FindingContext&) {
  return "nothing needed: the analysis took the mean interval as the period; --rate HZ sets "
         "it yourself";
}
std::string jitter_remedy(const FindingContext&) {
  return "stamp at the sensor (its sample counter or hardware time) if it can; when the "
         "samples themselves are regular, analyze with --rate HZ";
}
std::string nan_remedy(const FindingContext&) {
  return "nothing needed for a few rows; for many, fix the driver or logger (`imunoise check "
         "REC` counts them)";
}
std::string saturation_remedy(const FindingContext&) {
  return "record again at rest on a stable mount, or with a larger range setting: saturated "
         "samples bias every term";
}
std::string lsb_remedy(const FindingContext&) {
  return "nothing needed: Q in the verdict is this quantization (about LSB/√12); a finer "
         "output setting, where the sensor has one, lowers it";
}
std::string split_remedy(const FindingContext&) {
  return "nothing more needed; record without gaps for exact intervals (the intervals treat "
         "the pieces as one record of the total length)";
}
std::string interpolate_remedy(const FindingContext&) {
  return "analyze with --gaps split instead if the shortest τ matter (no invented samples)";
}
std::string hadamard_remedy(const FindingContext&) {
  return "fit on the Allan variance (the default of imunoise analyze) to estimate R";
}
std::string pooled_remedy(const FindingContext&) {
  return "nothing more needed (see the gap finding of the recording)";
}
std::string gm_bootstrap_remedy(const FindingContext&) {
  return "analyze again with --bootstrap 200 for intervals on σ and T_c of the Gauss-Markov "
         "terms";
}
/// The remedy of a failed PSD cross-check: one per likely cause the note names
/// (pipeline::psd_misfit_cause_text), the generic advice when it names none.
std::string psd_remedy(const FindingContext& c) {
  using analysis::PsdMisfitCause;
  constexpr std::array<std::pair<PsdMisfitCause, std::string_view>, 9> kRemedies{{
      {PsdMisfitCause::spectral_line,
       "a line inside the band named → analyze --sinusoid-hz F with its frequency F"},
      {PsdMisfitCause::isolated,
       "nothing for a single bin; if it recurs at the same frequency in other recordings, "
       "treat it as a line (analyze --sinusoid-hz F)"},
      {PsdMisfitCause::high_frequency_excess,
       "for vibration, record on an isolated mount; for noise folded from above Nyquist, "
       "record with the sensor's anti-alias filter on or at a higher rate"},
      {PsdMisfitCause::low_pass,
       "keep the low-pass check on (the default) or raise --tau-min above the filter's time "
       "constant; N stays right, the check band just reaches the roll-off"},
      {PsdMisfitCause::low_frequency_excess,
       "analyze --trim-start with the warm-up's length if the record starts warm-up, "
       "otherwise record longer so that K or R is identified"},
      {PsdMisfitCause::low_frequency_deficit,
       "look for a drift in the record (a ramp or warm-up fitted as a random walk): "
       "--trim-start cuts a warm-up"},
      {PsdMisfitCause::level,
       "compare the PSD figure with the model: the fit's N may be pulled by a Gauss-Markov "
       "term the selection left out (analyze --gauss-markov forces GM terms in) or by a "
       "low-pass (--tau-min)"},
      {PsdMisfitCause::band_excess,
       "analyze --gauss-markov to fit a correlated term in that band inside the selection"},
      {PsdMisfitCause::band_deficit,
       "compare the PSD figure with the model in that band; analyze --gauss-markov if a "
       "Gauss-Markov term would fit both"},
  }};
  std::string out;
  for (const auto& [cause, remedy] : kRemedies) {
    if (c.text.find(pipeline::psd_misfit_cause_text(cause)) == std::string_view::npos) continue;
    out += (out.empty() ? "" : "; ") + text(remedy);
  }
  if (!out.empty()) return out;
  return "look at the PSD figure of this axis: a line at F Hz → analyze --sinusoid-hz F; a "
         "roll-off towards Nyquist → keep the low-pass check on (the default) or raise "
         "--tau-min above the filter's time constant; excess at the lowest frequencies → cut "
         "the warm-up from the recording and analyze again";
}
std::string walk_or_ramp_remedy(const FindingContext&) {
  return "a record several times longer tells them apart (R grows like τ², K like τ); a "
         "known trend (temperature) is a ramp: remove it before the analysis";
}
std::string gm_choice_remedy(const FindingContext& c) {
  std::string remedy =
      "nothing to do; analyze --gauss-markov fits the GM terms inside the one model "
      "selection, --no-gauss-markov leaves them out";
  if (c.axis == nullptr || c.axis->gauss_markov_bounds.empty()) return remedy;
  // Where the data say most: the lowest point of the axis's bound curve (a GM the model does
  // not hold, of that T_c, is below it; analysis::gauss_markov_upper_bounds).
  const GaussMarkovBound* lowest = &c.axis->gauss_markov_bounds.front();
  for (const GaussMarkovBound& b : c.axis->gauss_markov_bounds)
    if (b.sigma_max < lowest->sigma_max) lowest = &b;
  const models::DatasheetUnit unit =
      models::datasheet_unit(NoiseTerm::bias_instability, c.axis->kind);
  return remedy + "; a further GM term is bounded by model.yaml's gauss_markov_upper_bound (" +
         std::to_string(c.axis->gauss_markov_bounds.size()) +
         " correlation times), most tightly sigma < " +
         significant_number_text(lowest->sigma_max * unit.factor, 2) + " " +
         std::string(unit.ascii) + " at T_c = " + significant_number_text(lowest->tau_c_s, 3) +
         " s";
}
std::string drift_motion_remedy(const FindingContext&) {
  return "record again on a still mount; imunoise drift --force runs anyway";
}
std::string drift_nees_remedy(const FindingContext& c) {
  return "check the model against its own simulation with imunoise drift REC --model " +
         text(c.model_path) +
         " --monte-carlo 100; refit with a longer record or analyze --gauss-markov";
}

// The one table of finding kinds. Markers are taken from the producers' texts:
// pipeline/data_quality.cpp (quality_findings), pipeline/gap_policy.cpp (plan_gaps notes),
// analysis/noise_fit.cpp (selection notes), pipeline/axis_analysis.cpp (fit and PSD notes),
// report/report_page.cpp (drift). Order matters where one marker contains another's text.
constexpr std::array<FindingKind, 22> kFindingKinds{{
    {"gaps_split", FindingSource::data_quality, "the curves and the PSD are pooled over ",
     "the record has time-stamp gaps; --gaps split analysed the gap-free pieces and pooled "
     "their curves",
     split_remedy},
    {"gaps_interpolated", FindingSource::data_quality, " linearly interpolated sample(s) per",
     "--gaps interpolate filled short gaps with straight lines, which are noise-free, so the "
     "shortest τ read slightly low",
     interpolate_remedy},
    {"time_gaps", FindingSource::data_quality, " time-stamp gap(s), longest ",
     "samples were lost or the logger paused: driver buffer overruns, a busy bus or host, or "
     "logs joined end to end",
     gaps_remedy},
    {"non_monotonic_stamps", FindingSource::data_quality, "non-monotonic time stamp(s)",
     "time stamps go backwards: a clock step or reset, files joined out of order, or several "
     "sensors' messages interleaved",
     stamp_order_remedy},
    {"duplicate_stamps", FindingSource::data_quality, "duplicate time stamp(s)",
     "the same stamp twice: a stamp clock coarser than the sample period, or a message logged "
     "twice",
     duplicate_remedy},
    {"quantized_stamps", FindingSource::data_quality, "time stamps quantized or alternating",
     "the stamp clock is coarser than the sample period, or the stamps alternate between two "
     "spacings",
     quantized_stamps_remedy},
    {"stamp_jitter", FindingSource::data_quality, "time-stamp jitter ",
     "stamps taken when messages arrive on the host (bus latency, scheduling), not at the "
     "sampling instant",
     jitter_remedy},
    {"non_finite_rows", FindingSource::data_quality, "row(s) with NaN/Inf dropped",
     "the driver or logger wrote NaN/Inf for reads that failed", nan_remedy},
    {"saturation", FindingSource::data_quality, "samples in saturation runs at the range limits",
     "the signal stuck at the range limits: motion or shock while recording, or a range set "
     "too small",
     saturation_remedy},
    {"full_scale", FindingSource::data_quality, "samples at or beyond the full scale",
     "the signal reached the full scale: motion or shock while recording, or a range set too "
     "small",
     saturation_remedy},
    {"output_lsb", FindingSource::data_quality, ": output quantized, LSB ",
     "the sensor outputs whole steps of this size (integer counts)", lsb_remedy},
    {"ramp_hadamard", FindingSource::fit_note, "the Hadamard variance is blind to a ramp",
     "the fit used the Hadamard variance, whose second difference removes a linear drift",
     hadamard_remedy},
    {"term_zero", FindingSource::fit_note, " not identified (NNLS zero",
     "the non-negative fit gave the term zero: the curve shows none of its slope in the "
     "fitted τ range",
     term_remedy},
    {"term_dropped", FindingSource::fit_note, " dropped: deviance drop ",
     "the term improved the fit by less than its penalty (model selection, theory.md §4.3): "
     "the data do not support it",
     term_remedy},
    {"pieces_pooled", FindingSource::fit_note, "curves pooled over ",
     "the record was split at its gaps and the curves of the pieces pooled", pooled_remedy},
    {"gm_needs_bootstrap", FindingSource::fit_note, "Gauss-Markov intervals need the bootstrap",
     "σ and T_c of a Gauss-Markov term enter the model nonlinearly; the least-squares "
     "intervals do not cover them",
     gm_bootstrap_remedy},
    {"ramp_as_random_walk", FindingSource::fit_note, "ramp replaced by random_walk",
     "a ramp and a random walk both rise at the longest τ, where few estimates are; K in the "
     "ramp's place fitted almost as well, and K is the stationary sensor's term",
     walk_or_ramp_remedy},
    {"gm_model_compared", FindingSource::fit_note, "Gauss-Markov model ",
     "the model with Gauss-Markov terms and the power-law model were fitted apart and the one "
     "with the lower penalized deviance D + p·κ·n_used/n_eff was kept (theory.md §4.3)",
     gm_choice_remedy},
    {"gm_none", FindingSource::fit_note, "no Gauss-Markov term identified",
     "the fit with Gauss-Markov terms kept none: the curve shows no correlated bump that the "
     "power-law terms do not already fit",
     gm_choice_remedy},
    {"psd_check_failed", FindingSource::psd_check, "PSD bins outside their 99 % interval",
     "the measured PSD leaves the fitted model's 99 % band in more bins than chance allows "
     "(theory.md §5.4): most often a spectral line (vibration, a fan or motor, a switching "
     "regulator), the sensor's low-pass filter near the top of the band, or a non-stationary "
     "start (warm-up) at the bottom",
     psd_remedy},
    {"drift_not_stationary", FindingSource::drift, "does not look stationary",
     "the signals vary more than at rest: the IMU moved during the recording", drift_motion_remedy},
    {"drift_nees_outside", FindingSource::drift, "is outside its 95 % band",
     "the recorded drift differs from the model's prediction beyond chance: the model misses "
     "a term at long τ (often B or K), or the recording has a disturbance there",
     drift_nees_remedy},
}};

/// The kind of a finding whose text says its own cause and remedy ("…; cause: X; remedy: Y"),
/// as newer checks may write them.
bool self_explained(std::string_view t, std::string& cause, std::string& remedy) {
  const std::size_t c = t.find("cause: ");
  const std::size_t r = t.find("remedy: ");
  if (c == std::string_view::npos || r == std::string_view::npos || r < c) return false;
  std::string_view cause_text = t.substr(c + 7, r - c - 7);
  while (!cause_text.empty() && (cause_text.back() == ' ' || cause_text.back() == ';' ||
                                 cause_text.back() == ',' || cause_text.back() == '('))
    cause_text.remove_suffix(1);
  std::string_view remedy_text = t.substr(r + 8);
  while (!remedy_text.empty() && (remedy_text.back() == ')' || remedy_text.back() == ' '))
    remedy_text.remove_suffix(1);
  cause = text(cause_text);
  remedy = text(remedy_text);
  return !cause.empty() && !remedy.empty();
}

std::string bound_text(double value, const models::DatasheetUnit& unit) {
  return significant_number_text(value * unit.factor, 2) + " " + text(unit.ascii);
}

std::string hours_text(double seconds) { return significant_number_text(seconds / 3600.0, 2); }

/// The τ range where BOUND²·φ_TERM(τ) ≥ the AVAR of REST, on a grid of 20 points per decade
/// from 1 µs to 10⁹ s; {0, 0} when nowhere.
std::pair<double, double> visible_range(const NoiseCoefficients& rest, NoiseTerm term,
                                        double bound) {
  double low = 0.0, high = 0.0;
  for (int k = -120; k <= 180; ++k) {
    const double tau = std::pow(10.0, k / 20.0);
    if (bound * bound * analysis::term_avar_basis(term, tau) >= analysis::model_avar(rest, tau)) {
      if (low == 0.0) low = tau;
      high = tau;
    }
  }
  return {low, high};
}

NoiseCoefficients without(const models::AxisModel& axis, NoiseTerm term) {
  NoiseCoefficients rest = axis.coefficients();
  coefficient(rest, term) = 0.0;
  return rest;
}

}  // namespace

std::span<const FindingKind> finding_kinds() { return kFindingKinds; }

const FindingKind* classify_finding(std::string_view t) {
  for (const FindingKind& kind : kFindingKinds)
    if (t.find(kind.marker) != std::string_view::npos) return &kind;
  return nullptr;
}

ExplainedFinding explain_finding(std::string where, const FindingContext& context) {
  ExplainedFinding out;
  out.where = std::move(where);
  out.text = text(context.text);
  if (const FindingKind* kind = classify_finding(context.text)) {
    out.kind = text(kind->id);
    out.cause = text(kind->cause);
    out.remedy = kind->remedy(context);
  } else if (self_explained(context.text, out.cause, out.remedy)) {
    out.kind = "self_explained";
  } else {
    out.kind = text(kUnknownFindingKind);
    out.cause =
        "not one this version of the report explains (a newer check, or another tool's "
        "note): read its text above";
    out.remedy =
        "`imunoise check REC` reruns the sampling checks; the detail tables below show "
        "what the fit used";
  }
  // The remedies say REC for the recording; name it when the model knows it.
  if (context.model && !context.model->source.empty()) {
    for (std::size_t at = out.remedy.find(" REC"); at != std::string::npos;
         at = out.remedy.find(" REC", at + 1)) {
      const std::size_t after = at + 4;
      if (after < out.remedy.size() && out.remedy[after] != ' ' && out.remedy[after] != '`')
        continue;
      out.remedy.replace(at + 1, 3, context.model->source);
    }
  }
  return out;
}

std::vector<ExplainedFinding> explain_model_findings(const models::NoiseModel& model,
                                                     std::string_view model_path) {
  std::vector<ExplainedFinding> out;
  for (const std::string& line : model.data_quality) {
    out.push_back(explain_finding("recording", {line, &model, nullptr, model_path}));
  }
  for (const models::AxisModel& axis : model.axes) {
    if (axis.psd_check_pass && !*axis.psd_check_pass) {
      out.push_back(explain_finding(axis.name, {axis.psd_check_note, &model, &axis, model_path}));
    }
    std::string_view note = axis.fit_note;
    while (!note.empty()) {
      const std::size_t end = note.find("; ");
      const std::string_view part = note.substr(0, end);
      if (!part.empty())
        out.push_back(explain_finding(axis.name, {part, &model, &axis, model_path}));
      if (end == std::string_view::npos) break;
      note.remove_prefix(end + 2);
    }
  }
  return out;
}

std::optional<double> duration_to_show_term(const models::AxisModel& axis, NoiseTerm term,
                                            double duration_s) {
  const double bound = axis.terms[term].ci_high;
  if (!(bound > 0.0) || !(axis.fit_tau_max_s > 0.0) || !(duration_s > 0.0)) return std::nullopt;
  const auto [low, high] = visible_range(without(axis, term), term, bound);
  if (low == 0.0 || low <= axis.fit_tau_max_s) return std::nullopt;
  // The fit's longest τ grows in proportion to the record (the τ grid and its EDF filter
  // scale with the length), so the fit reaches τ = low at duration × low / τ_max.
  (void)high;
  return duration_s * low / axis.fit_tau_max_s;
}

std::string unidentified_term_remedy(const models::AxisModel& axis, NoiseTerm term,
                                     double duration_s, double sample_rate_hz) {
  const models::DatasheetUnit unit = models::datasheet_unit(term, axis.kind);
  const double bound = axis.terms[term].ci_high;
  const std::string symbol = text(term_symbol(term));
  if (!(bound > 0.0)) {
    return "the fitted τ range gives no upper bound on " + symbol +
           "; a longer record (or a wider --tau-min/--tau-max range) gives one";
  }
  const auto [low, high] = visible_range(without(axis, term), term, bound);
  const std::string at_bound = "at its upper bound (" + bound_text(bound, unit) + ") " + symbol;
  if (low == 0.0) {
    return at_bound +
           " stays below the rest of the model at every τ, so no record length shows it; "
           "filters take the bound (imunoise export --strict refuses it instead)";
  }
  if (const std::optional<double> needed = duration_to_show_term(axis, term, duration_s)) {
    return at_bound + " would show from τ ≈ " + significant_number_text(low, 2) +
           " s, beyond the fitted range (up to " + significant_number_text(axis.fit_tau_max_s, 2) +
           " s): record at least " + hours_text(*needed) + " h (" +
           hours_text(*needed - duration_s) + " h more) to identify " + symbol +
           " at that level; a smaller " + symbol + " needs longer";
  }
  if (sample_rate_hz > 0.0 && high < 1.0 / sample_rate_hz) {
    return at_bound + " would show only below τ ≈ " + significant_number_text(high, 2) +
           " s, shorter than the sample period (" +
           significant_number_text(1.0 / sample_rate_hz, 2) +
           " s): only an output rate of at least " + significant_number_text(1.0 / high, 2) +
           " Hz shows it; filters take the bound";
  }
  if (high < axis.fit_tau_min_s) {
    return at_bound + " would show only below τ ≈ " + significant_number_text(high, 2) +
           " s, under the fitted range (from " + significant_number_text(axis.fit_tau_min_s, 2) +
           " s): lower --tau-min, or --no-low-pass-check if the low-pass check cut the short τ";
  }
  return at_bound + " would show inside the fitted τ range (" +
         significant_number_text(axis.fit_tau_min_s, 2) + "–" +
         significant_number_text(axis.fit_tau_max_s, 2) +
         " s), so it is smaller than the bound; nothing to do: filters take the bound";
}

std::optional<NoiseTerm> leading_term(std::string_view note) {
  for (NoiseTerm term : kNoiseTerms) {
    const std::string_view name = term_name(term);
    if (note.substr(0, name.size()) == name && note.size() > name.size() &&
        note[name.size()] == ' ')
      return term;
  }
  return std::nullopt;
}

}  // namespace imunoise::report
