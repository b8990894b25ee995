#include "tools/analysis_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "io/duration_parser.h"
#include "io/fftw_wisdom.h"
#include "io/fleet_spec.h"
#include "io/stage_progress.h"
#include "io/terminal_progress_bar.h"
#include "pipeline/gap_policy.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

constexpr std::string_view kGapsFlag = "--gaps";

pipeline::AxisAnalysisOptions axis_options(const AnalysisSettings& s, double tau0_s) {
  if (!(s.confidence > 0.0 && s.confidence < 1.0)) {
    throw InputError("--confidence: expected a level in (0, 1), got " +
                     shortest_number_text(s.confidence));
  }
  if (s.bootstrap && (*s.bootstrap == 1 || *s.bootstrap < 0)) {
    throw InputError("--bootstrap: expected 0 (least-squares intervals) or at least 2 replicates");
  }
  if (s.interval_draws == 1 || s.interval_draws < 0) {
    throw InputError("--interval-draws: expected 0 (least-squares intervals) or at least 2");
  }
  pipeline::AxisAnalysisOptions options;
  options.confidence = s.confidence;
  options.grid = analysis::parse_tau_grid(s.taus);
  // Intervals: by default the fitted model's OAVAR vectors drawn from their distribution
  // (cost independent of the record); --bootstrap N simulates whole records instead.
  options.interval_source = s.bootstrap ? pipeline::ReplicateSource::simulated_record
                                        : pipeline::ReplicateSource::variance_distribution;
  options.bootstrap_replicates = s.bootstrap ? *s.bootstrap : s.interval_draws;
  options.bootstrap_setting = "--bootstrap N or --interval-draws N";
  options.seed = s.seed;
  options.fit.gauss_markov = s.gauss_markov      ? analysis::GaussMarkovMode::on
                             : s.no_gauss_markov ? analysis::GaussMarkovMode::off
                                                 : analysis::GaussMarkovMode::automatic;
  options.fit.tau_min_s = s.tau_min_s;
  for (double f : s.sinusoid_hz) {
    if (!(f > 0.0) || !(f < 0.5 / tau0_s)) {
      throw InputError("--sinusoid-hz: " + shortest_number_text(f) +
                       " Hz is not in (0, Nyquist = " + shortest_number_text(0.5 / tau0_s) +
                       " Hz)");
    }
  }
  options.fit.sinusoid_frequencies_hz = s.sinusoid_hz;
  options.find_lines = !s.no_lines;
  options.fit.tau_max_s = s.tau_max_s;
  if (!(s.min_edf >= 1.0 && s.min_edf <= 100.0))
    throw InputError("--min-edf: expected an EDF in [1, 100], got " +
                     shortest_number_text(s.min_edf));
  options.fit.min_edf = s.min_edf;
  options.auto_low_pass = !s.no_low_pass_check;
  if (s.estimator != "wnnls" && s.estimator != "gls")
    throw InputError("--estimator: expected wnnls or gls, got '" + s.estimator + "'");
  options.generalized_least_squares = s.estimator == "gls";
  return options;
}

}  // namespace

void add_analysis_options(CLI::App& cmd, AnalysisSettings& s) {
  const std::string group = "Analysis";
  cmd.add_option("--taus", s.taus, "tau grid: octave, decade, log:N (default log:10)")
      ->group(group);
  cmd.add_option("--confidence", s.confidence, "interval level (default 0.95)")->group(group);
  cmd.add_option("--interval-draws", s.interval_draws,
                 "intervals from this many OAVAR vectors per axis drawn from their distribution "
                 "under the fitted model (its covariance across tau; default 200; 0 = "
                 "least-squares intervals, which ignore the correlation between tau points)")
      ->group(group);
  cmd.add_option("--bootstrap", s.bootstrap,
                 "instead: the parametric bootstrap of N simulated records per axis (N >= 2; "
                 "costs N analyses of the record; for validation), or 0 = least-squares "
                 "intervals")
      ->group(group);
  cmd.add_option("--seed", s.seed, "seed of the interval draws or the bootstrap (default 1)")
      ->group(group);
  cmd.add_option("--threads", s.threads, "worker threads (0 = all cores)")->group(group);
  CLI::Option* gm = cmd.add_flag("--gauss-markov", s.gauss_markov,
                                 "fit first-order Gauss-Markov terms together with the power-law "
                                 "terms in one model selection (default: the model with GM "
                                 "terms is fitted apart and kept only when its penalized "
                                 "deviance is lower than the power-law model's)")
                        ->group(group);
  cmd.add_flag("--no-gauss-markov", s.no_gauss_markov,
               "no Gauss-Markov terms: power-law terms and sinusoids only")
      ->excludes(gm)
      ->group(group);
  cmd.add_option("--sinusoid-hz", s.sinusoid_hz,
                 "sinusoid frequencies F1,F2,... [Hz] fitted (on the samples, frequency refined "
                 "within one PSD bin) and removed before the fit even when the automatic line "
                 "search does not find them")
      ->delimiter(',')
      ->group(group);
  cmd.add_flag("--no-lines", s.no_lines,
               "no automatic spectral-line search (by default lines standing above the local "
               "PSD continuum, false-alarm probability 1 % per channel, are fitted and removed)")
      ->group(group);
  cmd.add_option("--estimator", s.estimator,
                 "coefficient estimator of the selected model: wnnls (default: re-weighted NNLS "
                 "with the tau points taken as independent) or gls (generalized least squares "
                 "with their correlation under the fitted model; docs/validation.md compares "
                 "them)")
      ->group(group);
  cmd.add_option("--tau-min", s.tau_min_s, "fit only tau >= this [s]")->group(group);
  cmd.add_option("--tau-max", s.tau_max_s, "fit only tau <= this [s]")->group(group);
  cmd.add_option("--min-edf", s.min_edf,
                 "fit only tau whose equivalent degrees of freedom are at least this (default " +
                     shortest_number_text(analysis::FitOptions{}.min_edf) +
                     "; the longest tau of a record have the fewest)")
      ->group(group);
  cmd.add_flag("--no-low-pass-check", s.no_low_pass_check,
               "keep the shortest tau even where the curve bends below the white-noise line")
      ->group(group);
  cmd.add_option("--gaps", s.gaps,
                 "time-stamp gaps: refuse (the statistics assume uniform sampling), "
                 "split (analyse the gap-free pieces and pool them; pieces under " +
                     std::to_string(pipeline::kMinPieceSamples) +
                     " samples dropped) or interpolate (fill each gap linearly; gaps over 1 % "
                     "of the record or 1000 samples refused)")
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--outliers", s.outliers,
                 "outliers (samples beyond 4 robust scales of the residual to their neighbours' "
                 "median), when they carry a finding: keep, clip (to the threshold) or drop "
                 "(each replaced by its local mean plus white noise of the robust sigma, so the "
                 "sampling stays regular and N unbiased)")
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--trim-start", s.trim_start,
                 "drop this much of the start (e.g. 20min, 600s; 0 = keep everything); default: "
                 "the automatic trim of a detected warm-up transient (stated in model.yaml's "
                 "data_quality and the summary)")
      ->group(group);
  cmd.add_flag("--temperature-compensate", s.temperature_compensate,
               "with a temperature column: subtract each channel's bias-vs-temperature "
               "coefficient x (T - mean T) before the fit (the coefficient is reported either "
               "way)")
      ->group(group);
  cmd.add_option("--spec", s.spec,
                 "the sensor's datasheet spec YAML (the format of 'imunoise fleet --spec': per "
                 "sensor and term a value in datasheet units): a white noise N at least sqrt(2) "
                 "x the datasheet's gets the finding 'output likely decimated without "
                 "averaging', which the data alone cannot show")
      ->group(group);
  cmd.add_option(
         "--fftw-wisdom", s.fftw_wisdom,
         "FFTW wisdom file from 'imunoise fftw-wisdom': the PSD transforms use its "
         "measured plans (default: $IMUNOISE_FFTW_WISDOM; none, or '': FFTW_ESTIMATE plans)")
      ->group(group);
}

pipeline::GapPolicy gap_policy_option(const AnalysisSettings& settings) {
  return pipeline::parse_gap_policy(settings.gaps, kGapsFlag);
}

std::string import_fftw_wisdom_option(const AnalysisSettings& settings) {
  std::string path;
  if (settings.fftw_wisdom) {
    path = *settings.fftw_wisdom;  // "" switches the environment's file off
  } else if (const char* env = std::getenv("IMUNOISE_FFTW_WISDOM")) {
    path = env;
  }
  if (!path.empty()) io::import_fftw_wisdom(path);
  return path;
}

pipeline::RecordingAnalysisOptions recording_analysis_options(const AnalysisSettings& settings,
                                                              double tau0_s) {
  pipeline::RecordingAnalysisOptions options;
  options.axis = axis_options(settings, tau0_s);
  options.gaps = gap_policy_option(settings);
  options.gap_policy_setting = kGapsFlag;
  options.outliers = pipeline::parse_outlier_policy(settings.outliers, "--outliers");
  options.outlier_setting = "--outliers";
  if (settings.trim_start) {
    options.trim_start_s = io::parse_duration_s(*settings.trim_start, "--trim-start", true);
  }
  options.trim_setting = "--trim-start";
  options.temperature_compensate = settings.temperature_compensate;
  options.temperature_setting = "--temperature-compensate";
  options.low_pass_setting = "--no-low-pass-check";
  if (!settings.spec.empty()) options.spec = io::read_fleet_spec(settings.spec);
  options.threads = settings.threads;
  return options;
}

namespace {

/// RUN(options, channel feedback) with the options of SETTINGS and FEEDBACK fed from the
/// channels of RECORDING.
template <class Run>
pipeline::RecordingAnalysis run_with_feedback(const pipeline::Recording& recording,
                                              const AnalysisSettings& settings,
                                              const AnalysisFeedback& feedback, Run&& run) {
  const pipeline::RecordingAnalysisOptions options =
      recording_analysis_options(settings, recording.sample_period_s);
  std::size_t channels = 0;
  for (const char* name : pipeline::kImuChannelNames) {
    if (recording.find_channel(name) != nullptr) ++channels;
  }
  const std::int64_t units_per_channel =
      4 + (options.axis.bootstrap_replicates >= 2 ? options.axis.bootstrap_replicates : 0);
  io::ChannelProgress progress(channels, units_per_channel, feedback.bar, feedback.channel_times);
  pipeline::ChannelFeedback channel_feedback;
  channel_feedback.progress = [&progress](std::size_t i) { return progress.callback(i); };
  channel_feedback.channel_finished = [&progress] { progress.channel_finished(); };
  return run(options, channel_feedback);
}

}  // namespace

pipeline::RecordingAnalysis analyze_recording(const pipeline::Recording& recording,
                                              const std::string& source,
                                              const AnalysisSettings& settings,
                                              const AnalysisFeedback& feedback) {
  return run_with_feedback(recording, settings, feedback, [&](const auto& options, const auto& f) {
    return pipeline::analyze_recording(recording, source, options, f);
  });
}

pipeline::RecordingAnalysis analyze_recording_freeing_time_stamps(
    pipeline::Recording& recording, const std::string& source, const AnalysisSettings& settings,
    const AnalysisFeedback& feedback) {
  return run_with_feedback(recording, settings, feedback, [&](const auto& options, const auto& f) {
    return pipeline::analyze_recording_freeing_time_stamps(recording, source, options, f);
  });
}

}  // namespace imunoise::tools
