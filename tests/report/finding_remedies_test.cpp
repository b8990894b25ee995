// Tests of report/finding_remedies.h: the one table of finding kinds. Completeness is checked
// against the real producers — pipeline::quality_findings, pipeline::plan_gaps notes, the fit
// notes of analysis::fit_noise_model and pipeline::analyze_axis_pieces, the PSD cross-check note
// and the drift findings of the report page: every finding they emit is recognised, and every
// row of the table is reached by one of them. A text no row knows gets the generic cause and
// remedy; the record length that would show a term is checked against the closed form.
#include "report/finding_remedies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "analysis/noise_fit.h"
#include "analysis/noise_terms.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/data_quality.h"
#include "pipeline/gap_policy.h"
#include "pipeline/recording.h"
#include "report/report_page.h"
#include "test_support.h"

namespace imunoise::report {
namespace {

/// Every finding text the producers emit, with the axis model it belongs to (if any).
struct Emitted {
  std::string text;
  models::AxisModel axis;
  bool has_axis = false;
};

void add_note_parts(std::vector<Emitted>& out, const models::AxisModel& axis) {
  std::string_view note = axis.fit_note;
  while (!note.empty()) {
    const std::size_t end = note.find("; ");
    out.push_back({std::string(note.substr(0, end)), axis, true});
    if (end == std::string_view::npos) break;
    note.remove_prefix(end + 2);
  }
}

std::vector<Emitted> data_quality_findings() {
  pipeline::SamplingReport report;
  pipeline::TimingReport& t = report.timing;
  t.has_timestamps = true;
  t.median_interval_s = 0.01;
  t.mean_interval_s = 0.0102;
  t.period_from_mean = true;
  t.gap_count = 2;
  t.longest_gap_s = 0.5;
  t.missing_samples = 60;
  t.non_monotonic_count = 1;
  t.duplicate_count = 3;
  t.jitter_rms_s = 0.001;
  report.rows_dropped = 4;
  pipeline::ChannelReport c;
  c.name = "gyro_x";
  c.unit = "rad/s";
  c.saturated_samples = 10;
  c.beyond_full_scale = 12;
  c.lsb = 1e-4;
  report.channels.push_back(c);
  std::vector<Emitted> out;
  for (const std::string& line : pipeline::quality_findings(report)) out.push_back({line, {}});
  EXPECT_EQ(out.size(), 9u) << "quality_findings emits a line this test does not expect";
  return out;
}

std::vector<Emitted> gap_plan_notes() {
  // 10 000 samples at 100 Hz with one 0.5 s gap after sample 5000.
  pipeline::Recording r;
  r.source_path = "rec.csv";
  r.sample_period_s = 0.01;
  for (int i = 0; i < 10000; ++i) r.time_s.push_back(0.01 * i + (i > 5000 ? 0.5 : 0.0));
  r.report.timing = pipeline::analyze_timing(r.time_s);
  pipeline::Channel ch;
  ch.name = "gyro_x";
  ch.kind = SensorKind::gyro;
  ch.values.assign(10000, 0.0);
  r.channels.push_back(ch);
  std::vector<Emitted> out;
  for (pipeline::GapPolicy policy : {pipeline::GapPolicy::split, pipeline::GapPolicy::interpolate})
    out.push_back({pipeline::plan_gaps(r, "rec.csv", policy, true).note, {}});
  return out;
}

/// White rate noise plus a first-order Gauss–Markov process (exact AR(1) of its samples),
/// analysed in two pieces with GM terms and no bootstrap: the pooled note, the GM-interval
/// note, the PSD note and the term notes of the fit.
std::vector<Emitted> axis_notes() {
  const double tau0 = 0.01, sigma_gm = 2e-3, tau_c = 2.0;
  const std::size_t n = 120000;
  std::vector<double> y = test::white_noise(n, 1e-3 / std::sqrt(tau0), 5);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g(0.0, 1.0);
  const double phi = std::exp(-tau0 / tau_c);
  double x = 0.0;
  for (double& v : y) {
    x = phi * x + sigma_gm * std::sqrt(1.0 - phi * phi) * g(rng);
    v += x;
  }
  const std::span<const double> all(y);
  const std::span<const double> pieces[] = {all.subspan(0, n / 2), all.subspan(n / 2)};
  pipeline::AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  options.fit.gauss_markov = analysis::GaussMarkovMode::on;
  const pipeline::AxisAnalysis a =
      pipeline::analyze_axis_pieces("gyro_x", SensorKind::gyro, pieces, tau0, 0, options);
  std::vector<Emitted> out;
  add_note_parts(out, a.model);
  out.push_back({a.model.psd_check_note, a.model, true});
  return out;
}

/// The fit notes of analysis::fit_noise_model on the closed-form AVAR of a white + random-walk
/// axis (theory.md §4.1) with large EDF: Q, B and R are zero or dropped; with the Hadamard
/// basis the ramp is not fitted at all.
std::vector<Emitted> fit_notes() {
  NoiseCoefficients c;
  c.white_noise = 1e-3;
  c.random_walk = 1e-5;
  std::vector<analysis::FitPoint> avar, hvar;
  for (double tau = 0.01; tau < 2000.0; tau *= 1.5) {
    const double edf = std::max(2.0, 2e5 / (tau / 0.01));
    avar.push_back({tau, analysis::model_avar(c, tau), edf});
    hvar.push_back({tau, analysis::model_hvar(c, tau), edf});
  }
  std::vector<Emitted> out;
  models::AxisModel axis;
  axis.name = "gyro_y";
  axis.fit_note = analysis::fit_noise_model(avar, {}).selection_note;
  add_note_parts(out, axis);
  NoiseCoefficients gm;  // the default fit compares the model with GM terms and keeps it
  gm.white_noise = 1e-3;
  gm.gauss_markov = {{1e-3, 20.0}};
  std::vector<analysis::FitPoint> gm_avar;
  for (const analysis::FitPoint& p : avar)
    gm_avar.push_back({p.tau_s, analysis::model_avar(gm, p.tau_s), p.edf});
  axis.fit_note = analysis::fit_noise_model(gm_avar, {}).selection_note;
  add_note_parts(out, axis);
  NoiseCoefficients ramp;  // a ramp seen only where the EDF is 2-6: K fits as well
  ramp.white_noise = 1e-3;
  ramp.ramp = 1e-6;
  std::vector<analysis::FitPoint> ramp_avar;
  for (const analysis::FitPoint& p : avar)
    ramp_avar.push_back({p.tau_s, analysis::model_avar(ramp, p.tau_s), p.edf});
  axis.fit_note = analysis::fit_noise_model(ramp_avar, {}).selection_note;
  add_note_parts(out, axis);
  analysis::FitOptions hadamard;
  hadamard.hadamard = true;
  axis.fit_note = analysis::fit_noise_model(hvar, hadamard).selection_note;
  add_note_parts(out, axis);
  return out;
}

/// The drift findings of the report page (report_page.cpp), through the verdict section.
std::vector<ExplainedFinding> drift_findings() {
  io::ResultsDirectory r;
  r.dir = "out";
  r.drift_dir = "out";
  pipeline::DriftSummary s;
  s.protocol = {60.0, 600.0, 5.0, 3, "height hold", "removed", "given heading", "peak_match"};
  s.motion.stationary = false;
  s.motion.reason = "the IMU tilts by 3 deg";
  pipeline::DriftConsistency c;
  c.time_s = 600.0;
  c.mean_nees = 9.5;
  c.nees_inside = false;
  c.nees_inside_joint_band = false;
  s.consistency.push_back(c);
  r.drift_summary = s;
  const ReportDocument doc = build_report_page(r, "now");
  EXPECT_EQ(doc.page.sections.front().id, "verdict");
  std::vector<ExplainedFinding> out;
  for (const FindingItem& f : doc.page.sections.front().findings) {
    const FindingKind* kind = classify_finding(f.text);
    out.push_back({f.where, f.text, kind ? std::string(kind->id) : "unknown", f.cause, f.remedy});
  }
  EXPECT_EQ(out.size(), 2u);
  return out;
}

TEST(FindingRemedies, EveryRowHasAnIdAMarkerACauseAndARemedy) {
  std::set<std::string> ids;
  const models::AxisModel axis;
  for (const FindingKind& kind : finding_kinds()) {
    EXPECT_TRUE(ids.insert(std::string(kind.id)).second) << "duplicate id " << kind.id;
    EXPECT_FALSE(kind.marker.empty()) << kind.id;
    EXPECT_GT(kind.cause.size(), 20u) << kind.id;
    const std::string remedy = kind.remedy({kind.marker, nullptr, &axis, "out/model.yaml"});
    EXPECT_GT(remedy.size(), 20u) << kind.id;
    // The row recognises its own marker (no earlier row shadows it).
    EXPECT_EQ(classify_finding(kind.marker), &kind) << kind.id;
  }
}

TEST(FindingRemedies, EveryFindingThePipelineEmitsIsKnownAndEveryKindIsEmitted) {
  std::set<std::string> seen;
  const auto check = [&](const std::vector<Emitted>& emitted) {
    for (const Emitted& e : emitted) {
      ASSERT_FALSE(e.text.empty());
      models::NoiseModel model;
      model.source = "rec.csv";
      model.duration_s = 3600.0;
      model.sample_rate_hz = 100.0;
      const ExplainedFinding f = explain_finding(
          "gyro_x", {e.text, &model, e.has_axis ? &e.axis : nullptr, "out/model.yaml"});
      EXPECT_NE(f.kind, kUnknownFindingKind) << "no row recognises: " << e.text;
      EXPECT_FALSE(f.cause.empty()) << e.text;
      EXPECT_FALSE(f.remedy.empty()) << e.text;
      EXPECT_EQ(f.remedy.find(" REC "), std::string::npos) << "placeholder left: " << f.remedy;
      seen.insert(f.kind);
    }
  };
  check(data_quality_findings());
  check(gap_plan_notes());
  check(axis_notes());
  check(fit_notes());
  for (const ExplainedFinding& f : drift_findings()) {
    EXPECT_NE(f.kind, kUnknownFindingKind) << f.text;
    EXPECT_FALSE(f.cause.empty() || f.remedy.empty()) << f.text;
    seen.insert(f.kind);
  }
  for (const FindingKind& kind : finding_kinds())
    EXPECT_TRUE(seen.count(std::string(kind.id))) << "no producer emitted kind " << kind.id;
}

TEST(FindingRemedies, UnknownTextGetsAGenericCauseAndRemedyAndSelfExplainedTextItsOwn) {
  const ExplainedFinding unknown = explain_finding("recording", {"something new happened"});
  EXPECT_EQ(unknown.kind, kUnknownFindingKind);
  EXPECT_EQ(unknown.text, "something new happened");
  EXPECT_NE(unknown.cause.find("not one this version"), std::string::npos);
  EXPECT_NE(unknown.remedy.find("imunoise check"), std::string::npos);
  const ExplainedFinding own = explain_finding(
      "recording",
      {"warm-up: the bias settles over the first 900 s (cause: thermal transient; remedy: "
       "trim the first 900 s)"});
  EXPECT_EQ(own.kind, "self_explained");
  EXPECT_EQ(own.cause, "thermal transient");
  EXPECT_EQ(own.remedy, "trim the first 900 s");
}

TEST(FindingRemedies, TheGaussMarkovChoiceNamesTheTightestPointOfTheBoundCurve) {
  models::AxisModel axis;
  axis.name = "gyro_y";
  axis.kind = SensorKind::gyro;
  const std::string text =
      "Gauss-Markov model not kept: penalized deviance 137 against 118 without GM terms";
  EXPECT_EQ(explain_finding("gyro_y", {text, nullptr, &axis}).remedy.find("gauss_markov_upper"),
            std::string::npos);
  // 4.848e-6 rad/s = 1 deg/h at T_c 300 s is the lowest point.
  axis.gauss_markov_bounds = {{30.0, 1e-5}, {300.0, 4.848136811e-6}, {3000.0, 2e-5}};
  const ExplainedFinding f = explain_finding("gyro_y", {text, nullptr, &axis});
  EXPECT_EQ(f.kind, "gm_model_compared");
  EXPECT_NE(f.remedy.find("gauss_markov_upper_bound (3 correlation times), most tightly sigma < 1 "
                          "deg/h at T_c = 300 s"),
            std::string::npos)
      << f.remedy;
}

TEST(FindingRemedies, TheRecordingIsNamedInTheRemedies) {
  models::NoiseModel model;
  model.source = "data/rec.csv";
  const ExplainedFinding f =
      explain_finding("recording", {"2 non-monotonic time stamp(s)", &model, nullptr, "m.yaml"});
  EXPECT_NE(f.remedy.find("`imunoise check data/rec.csv`"), std::string::npos) << f.remedy;
}

TEST(FindingRemedies, DurationToShowRandomWalkMatchesTheClosedForm) {
  // White noise N and a random walk K at its upper bound u: K²τ/3 = N²/τ at τ* = √3·N/u
  // (theory.md §4.1). The fit reached τ_max = 100 s in 1000 s, so the record must be
  // 1000·τ*/100 s long; the scan's grid (20 points per decade) puts τ* at most a factor
  // 10^(1/20) = 1.122 late.
  models::AxisModel axis;
  axis.name = "gyro_x";
  axis.terms[NoiseTerm::white_noise] = {1e-3, 0.9e-3, 1.1e-3, true, "", ""};
  axis.terms[NoiseTerm::random_walk] = {0.0, 0.0, 1e-6, false, "", ""};
  axis.fit_tau_min_s = 0.01;
  axis.fit_tau_max_s = 100.0;
  const double tau_star = std::sqrt(3.0) * 1e-3 / 1e-6;
  const std::optional<double> needed = duration_to_show_term(axis, NoiseTerm::random_walk, 1000.0);
  ASSERT_TRUE(needed.has_value());
  EXPECT_GE(*needed, 1000.0 * tau_star / 100.0);
  EXPECT_LE(*needed, 1000.0 * tau_star / 100.0 * 1.1221);
  const std::string remedy = unidentified_term_remedy(axis, NoiseTerm::random_walk, 1000.0, 100);
  EXPECT_NE(remedy.find("record at least "), std::string::npos) << remedy;
  EXPECT_NE(remedy.find(" h more) to identify K"), std::string::npos) << remedy;
  // A bound the fitted range already reaches: no record length is asked for.
  axis.fit_tau_max_s = 1e5;
  EXPECT_FALSE(duration_to_show_term(axis, NoiseTerm::random_walk, 1e6).has_value());
  EXPECT_NE(unidentified_term_remedy(axis, NoiseTerm::random_walk, 1e6, 100)
                .find("smaller than the bound"),
            std::string::npos);
  // Quantization at a bound that shows only below the sample period.
  axis.terms[NoiseTerm::quantization] = {0.0, 0.0, 1e-6, false, "", ""};
  EXPECT_NE(unidentified_term_remedy(axis, NoiseTerm::quantization, 1e6, 100)
                .find("only an output rate of at least"),
            std::string::npos);
  // No bound at all.
  axis.terms[NoiseTerm::ramp] = {};
  EXPECT_NE(unidentified_term_remedy(axis, NoiseTerm::ramp, 1e6, 100).find("no upper bound"),
            std::string::npos);
}

TEST(FindingRemedies, AFailedPsdCheckNamesItsBandsAndGetsTheRemedyOfEachLikelyCause) {
  // A failed check with a low-pass band at the top and a missing walk at the bottom, as
  // analysis::cross_check_psd() reports them: the note names both bands in Hz with their
  // causes, the kind is still psd_check_failed, and the remedy is the one of each cause.
  analysis::PsdCrossCheck check;
  check.bins_compared = 40;
  check.bins_outside = 9;
  check.f_min_hz = 0.0046;
  check.f_max_hz = 35.6;
  check.pass = false;
  check.misfits.push_back(
      {0.0046, 0.0072, 3, true, 2.4, analysis::PsdMisfitCause::low_frequency_excess});
  check.misfits.push_back({14.2, 35.6, 6, false, 0.064, analysis::PsdMisfitCause::low_pass});
  const std::string note = pipeline::psd_check_note(check);
  EXPECT_NE(note.find("9 of 40 PSD bins outside their 99 % interval (0.0046–35.6 Hz)"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("above the model at 0.0046–0.0072 Hz (3 bins, up to ×2.4): " +
                      std::string(pipeline::psd_misfit_cause_text(
                          analysis::PsdMisfitCause::low_frequency_excess))),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("below the model at 14.2–35.6 Hz (6 bins, up to ×0.064): likely the "
                      "sensor's low-pass filter"),
            std::string::npos)
      << note;
  models::AxisModel axis;
  const ExplainedFinding f = explain_finding("gyro_x", {note, nullptr, &axis, "model.yaml"});
  EXPECT_EQ(f.kind, "psd_check_failed");
  EXPECT_NE(f.remedy.find("--trim-start"), std::string::npos) << f.remedy;
  EXPECT_NE(f.remedy.find("--tau-min"), std::string::npos) << f.remedy;
  EXPECT_EQ(f.remedy.find("--sinusoid-hz"), std::string::npos) << f.remedy;
  // A passing check's note names no band; every cause has its own text.
  check.pass = true;
  EXPECT_EQ(pipeline::psd_check_note(check).find("model at"), std::string::npos);
  std::set<std::string> texts;
  for (int c = 0; c <= static_cast<int>(analysis::PsdMisfitCause::band_deficit); ++c)
    texts.insert(
        std::string(pipeline::psd_misfit_cause_text(static_cast<analysis::PsdMisfitCause>(c))));
  EXPECT_EQ(texts.size(), static_cast<std::size_t>(analysis::PsdMisfitCause::band_deficit) + 1);
}

}  // namespace
}  // namespace imunoise::report
