#include "tools/analysis_job.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "analysis/psd.h"
#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "io/fftw_wisdom.h"
#include "pipeline/gap_policy.h"
#include "tools/progress.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

pipeline::AxisAnalysisOptions axis_options(const AnalysisSettings& s, double tau0_s) {
  if (!(s.confidence > 0.0 && s.confidence < 1.0)) {
    throw InputError("--confidence: expected a level in (0, 1), got " +
                     shortest_number_text(s.confidence));
  }
  if (s.bootstrap == 1 || s.bootstrap < 0) {
    throw InputError("--bootstrap: expected 0 (off) or at least 2 replicates");
  }
  pipeline::AxisAnalysisOptions options;
  options.confidence = s.confidence;
  options.grid = analysis::parse_tau_grid(s.taus);
  options.bootstrap_replicates = s.bootstrap;
  options.seed = s.seed;
  options.fit.gauss_markov =
      s.gauss_markov ? analysis::GaussMarkovMode::on : analysis::GaussMarkovMode::off;
  options.fit.tau_min_s = s.tau_min_s;
  for (double f : s.sinusoid_hz) {
    if (!(f > 0.0) || !(f < 0.5 / tau0_s)) {
      throw InputError("--sinusoid-hz: " + shortest_number_text(f) +
                       " Hz is not in (0, Nyquist = " + shortest_number_text(0.5 / tau0_s) +
                       " Hz)");
    }
  }
  options.fit.sinusoid_frequencies_hz = s.sinusoid_hz;
  options.fit.tau_max_s = s.tau_max_s;
  options.auto_low_pass = !s.no_low_pass_check;
  return options;
}

/// Feeds one progress bar and the stage times from the channels analysed in parallel: the
/// bar's fraction is the sum of the channels' units over their total, its stage the one
/// reported last. Only atomics on the hot path; the times take a short lock on a stage change.
class ChannelProgress {
 public:
  ChannelProgress(std::size_t channels, const pipeline::AxisAnalysisOptions& options,
                  const AnalysisFeedback& feedback)
      : feedback_(feedback),
        done_(channels),
        stage_(channels),
        stage_start_(channels),
        units_per_channel_(4 +
                           (options.bootstrap_replicates >= 2 ? options.bootstrap_replicates : 0)),
        channels_(static_cast<std::int64_t>(channels)) {
    if (feedback_.bar != nullptr) feedback_.bar->set_items(0, channels_, "channels");
  }

  /// The callback of channel I (empty when nobody listens).
  ProgressCallback callback(std::size_t i) {
    if ((feedback_.bar == nullptr || !feedback_.bar->enabled()) &&
        feedback_.channel_times == nullptr) {
      return {};
    }
    return [this, i](std::string_view stage, std::int64_t done, std::int64_t) {
      std::int64_t seen = done_[i].load();
      while (done > seen && !done_[i].compare_exchange_weak(seen, done)) {
      }
      if (feedback_.channel_times != nullptr) time_stage(i, stage);
      if (feedback_.bar != nullptr) {
        std::int64_t sum = 0;
        for (const auto& d : done_) sum += d.load();
        feedback_.bar->update(stage, sum, units_per_channel_ * channels_);
      }
    };
  }

  void channel_finished() {
    const std::int64_t finished = ++finished_;
    if (feedback_.bar != nullptr) feedback_.bar->set_items(finished, channels_, "channels");
  }

 private:
  /// Closes the running stage of channel I when it changes (stages arrive in order per
  /// channel; bootstrap replicates repeat the same stage).
  void time_stage(std::size_t i, std::string_view stage) {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard<std::mutex> lock(times_mutex_);
    if (stage_[i] == stage) return;
    if (!stage_[i].empty()) {
      feedback_.channel_times->add(stage_[i],
                                   std::chrono::duration<double>(now - stage_start_[i]).count());
    }
    stage_[i].assign(stage);
    stage_start_[i] = now;
  }

  const AnalysisFeedback feedback_;
  std::vector<std::atomic<std::int64_t>> done_;
  std::vector<std::string> stage_;  // under times_mutex_
  std::vector<std::chrono::steady_clock::time_point> stage_start_;
  std::mutex times_mutex_;
  const std::int64_t units_per_channel_;
  const std::int64_t channels_;
  std::atomic<std::int64_t> finished_{0};
};

}  // namespace

void add_analysis_options(CLI::App& cmd, AnalysisSettings& s) {
  const std::string group = "Analysis";
  cmd.add_option("--taus", s.taus, "tau grid: octave, decade, log:N (default log:10)")
      ->group(group);
  cmd.add_option("--confidence", s.confidence, "interval level (default 0.95)")->group(group);
  cmd.add_option("--bootstrap", s.bootstrap,
                 "parametric bootstrap replicates per axis (default 50; 0 = least-squares "
                 "intervals, which ignore the correlation between tau points)")
      ->group(group);
  cmd.add_option("--seed", s.seed, "bootstrap seed (default 1)")->group(group);
  cmd.add_option("--threads", s.threads, "worker threads (0 = all cores)")->group(group);
  cmd.add_flag("--gauss-markov", s.gauss_markov,
               "also fit first-order Gauss-Markov terms (grid of correlation times, refined)")
      ->group(group);
  cmd.add_option("--sinusoid-hz", s.sinusoid_hz,
                 "candidate sinusoid frequencies F1,F2,... [Hz] (e.g. lines seen in psd.csv); "
                 "each amplitude is fitted and kept only if the data support it")
      ->delimiter(',')
      ->group(group);
  cmd.add_option("--tau-min", s.tau_min_s, "fit only tau >= this [s]")->group(group);
  cmd.add_option("--tau-max", s.tau_max_s, "fit only tau <= this [s]")->group(group);
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
  cmd.add_option(
         "--fftw-wisdom", s.fftw_wisdom,
         "FFTW wisdom file from 'imunoise fftw-wisdom': the PSD transforms use its "
         "measured plans (default: $IMUNOISE_FFTW_WISDOM; none, or '': FFTW_ESTIMATE plans)")
      ->group(group);
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

std::string psd_plan_text(const AnalysisResult& result) {
  if (result.axes.empty() || result.axes.front().psd.segment_length < 2) return "no PSD";
  const analysis::Spectrum& psd = result.axes.front().psd;
  std::string text = "PSD FFT plan (L = " + std::to_string(psd.segment_length) + "): ";
  text.append(psd.fft_plan_from_wisdom ? "from FFTW wisdom"
                                       : "FFTW_ESTIMATE (no wisdom for this length)");
  return text;
}

std::vector<std::string> quality_findings(const pipeline::SamplingReport& report) {
  std::vector<std::string> out;
  const pipeline::TimingReport& t = report.timing;
  if (t.gap_count > 0) {
    out.push_back(std::to_string(t.gap_count) + " time-stamp gap(s), longest " +
                  significant_number_text(t.longest_gap_s) + " s, about " +
                  std::to_string(t.missing_samples) + " samples missing");
  }
  if (t.non_monotonic_count > 0) {
    out.push_back(std::to_string(t.non_monotonic_count) + " non-monotonic time stamp(s)");
  }
  if (t.duplicate_count > 0) {
    out.push_back(std::to_string(t.duplicate_count) + " duplicate time stamp(s)");
  }
  if (t.has_timestamps && t.median_interval_s > 0.0 &&
      t.jitter_rms_s > 0.01 * t.median_interval_s) {
    out.push_back("time-stamp jitter " + significant_number_text(t.jitter_rms_s) + " s RMS (" +
                  significant_number_text(100.0 * t.jitter_rms_s / t.median_interval_s, 3) +
                  " % of the interval)");
  }
  if (report.rows_dropped > 0) {
    out.push_back(std::to_string(report.rows_dropped) + " row(s) with NaN/Inf dropped");
  }
  for (const pipeline::ChannelReport& c : report.channels) {
    if (c.saturated_samples > 0) {
      out.push_back(c.name + ": " + std::to_string(c.saturated_samples) +
                    " samples in saturation runs at the range limits");
    }
    if (c.beyond_full_scale > 0) {
      out.push_back(c.name + ": " + std::to_string(c.beyond_full_scale) +
                    " samples at or beyond the full scale");
    }
    if (c.lsb)
      out.push_back(c.name + ": output quantized, LSB " + shortest_number_text(*c.lsb) + " " +
                    c.unit);
  }
  return out;
}

std::string gap_refusal_message(const std::string& source, const pipeline::TimingReport& timing) {
  if (timing.gap_count <= 0) return {};
  std::string what = std::to_string(timing.gap_count) + " time-stamp gap(s)";
  if (timing.first_gap) {
    what.append(", the first before sample ").append(std::to_string(timing.first_gap->index));
    if (!timing.gaps.empty()) {
      what.append(" (t = ")
          .append(significant_number_text(timing.gaps.front().start_s, 9))
          .append(" s, ")
          .append(significant_number_text(timing.gaps.front().length_s))
          .append(" s long)");
    }
  }
  what.append(", the longest ")
      .append(significant_number_text(timing.longest_gap_s))
      .append(" s, about ")
      .append(std::to_string(timing.missing_samples))
      .append(
          " samples missing; the analysis needs uniformly spaced samples: use --gaps split "
          "(pool the gap-free pieces) or --gaps interpolate (fill linearly), or fix the "
          "recording");
  const std::int64_t line =
      timing.first_gap && timing.first_gap->line ? *timing.first_gap->line : 0;
  return located_message(source, line, 0, what);
}

namespace {

/// How the samples of every channel reach analyze_axis_pieces under the gap policy.
struct GapPlan {
  pipeline::GapPolicy policy = pipeline::GapPolicy::refuse;
  std::vector<pipeline::TimeGap> gaps;        ///< every gap (split, interpolate)
  std::vector<pipeline::SampleRange> pieces;  ///< split: kept pieces; else empty
  std::int64_t samples = 0;                   ///< samples analysed per channel
  std::string note;                           ///< data-quality line ("" without gaps)
};

/// Applies the policy to the recording's gaps: refuses (InputError), or plans the split or
/// the interpolation and words the data-quality line.
GapPlan plan_gaps(const pipeline::Recording& recording, const std::string& source,
                  pipeline::GapPolicy policy, bool bootstrap) {
  GapPlan plan;
  plan.policy = policy;
  const std::size_t n = recording.sample_count();
  plan.samples = static_cast<std::int64_t>(n);
  const pipeline::TimingReport& timing = recording.report.timing;
  if (timing.gap_count <= 0 || recording.time_s.size() != n || !(timing.median_interval_s > 0.0)) {
    return plan;
  }
  if (policy == pipeline::GapPolicy::refuse) {
    throw InputError(gap_refusal_message(source, timing));
  }
  plan.gaps = pipeline::find_time_gaps(recording.time_s, timing.median_interval_s);
  if (plan.gaps.empty()) return plan;
  const std::string count = std::to_string(plan.gaps.size()) + " time-stamp gap(s)";
  if (policy == pipeline::GapPolicy::split) {
    const pipeline::GapSplit split =
        pipeline::split_at_gaps(n, plan.gaps, pipeline::kMinPieceSamples);
    if (split.pieces.empty()) {
      throw AnalysisError(source + ": --gaps split: no gap-free piece has " +
                          std::to_string(pipeline::kMinPieceSamples) + " samples or more (" +
                          count + " cut " + std::to_string(n) + " samples into " +
                          std::to_string(split.dropped_pieces) + " pieces)");
    }
    plan.pieces = split.pieces;
    plan.samples = 0;
    for (const auto& piece : plan.pieces) plan.samples += static_cast<std::int64_t>(piece.size());
    plan.note = "--gaps split: " + count + "; the curves and the PSD are pooled over " +
                std::to_string(plan.pieces.size()) + " gap-free piece(s) (" +
                std::to_string(plan.samples) + " samples)";
    if (split.dropped_pieces > 0) {
      plan.note += "; " + std::to_string(split.dropped_pieces) + " piece(s) shorter than " +
                   std::to_string(pipeline::kMinPieceSamples) + " samples dropped (" +
                   std::to_string(split.dropped_samples) + " samples)";
    }
    if (bootstrap) {
      plan.note += "; bootstrap intervals simulate one record of the total length (approximate)";
    }
    return plan;
  }
  // Interpolate: every gap must be short enough for a straight line to be harmless.
  const std::int64_t limit = pipeline::max_interpolated_gap(n);
  std::int64_t filled = 0;
  for (const pipeline::TimeGap& g : plan.gaps) {
    if (g.missing > limit) {
      std::string at = "sample " + std::to_string(g.after);
      if (recording.report.timing.first_gap && recording.report.timing.first_gap->line &&
          recording.report.timing.first_gap->index == static_cast<std::int64_t>(g.after)) {
        at.append(", line ").append(std::to_string(*recording.report.timing.first_gap->line));
      }
      throw InputError(source + ": --gaps interpolate: the gap before " + at +
                       " (t = " + significant_number_text(g.start_s, 9) + " s, " +
                       significant_number_text(g.length_s) + " s long) lacks " +
                       std::to_string(g.missing) + " samples, more than interpolation may fill (" +
                       std::to_string(limit) +
                       ": 1 % of the record, at most 1000); use --gaps split");
    }
    filled += g.missing;
  }
  plan.samples += filled;
  plan.note = "--gaps interpolate: " + count + " filled with " + std::to_string(filled) +
              " linearly interpolated sample(s) per channel (noise-free, so the shortest tau "
              "read slightly low)";
  return plan;
}

}  // namespace

namespace {

/// analyze_recording; when RELEASE is given (it is RECORDING's time_s), the time stamps are
/// freed as soon as the gaps are planned: nothing after the plan reads them.
AnalysisResult analyze(const pipeline::Recording& recording, const std::string& source,
                       const AnalysisSettings& settings, const AnalysisFeedback& feedback,
                       std::vector<double>* release) {
  const double tau0_s = recording.sample_period_s;
  // The readers guarantee a positive period; a Recording built by other code might not, and
  // τ0 = 0 would turn every τ and rate into 0 or Inf.
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) {
    throw InputError(source + ": no usable sample period (" + shortest_number_text(tau0_s) +
                     " s): give the rate or a time column that increases");
  }
  std::vector<std::pair<std::size_t, const pipeline::Channel*>> channels;
  for (std::size_t c = 0; c < pipeline::kImuChannelNames.size(); ++c) {
    if (const pipeline::Channel* channel = recording.find_channel(pipeline::kImuChannelNames[c])) {
      channels.emplace_back(c, channel);
    }
  }
  if (channels.empty()) {
    throw InputError(source + ": no gyro or accelerometer channels to analyse");
  }
  const pipeline::AxisAnalysisOptions options = axis_options(settings, tau0_s);
  const GapPlan gap_plan = plan_gaps(recording, source, pipeline::parse_gap_policy(settings.gaps),
                                     settings.bootstrap >= 2);
  if (release != nullptr) std::vector<double>().swap(*release);
  // The samples each channel is analysed on: the recording, its gap-free pieces, or a copy
  // with the gaps filled (kept alive here for the spans).
  std::vector<std::vector<double>> filled(channels.size());
  std::vector<std::vector<std::span<const double>>> pieces(channels.size());
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::vector<double>& values = channels[i].second->values;
    if (gap_plan.policy == pipeline::GapPolicy::interpolate && !gap_plan.gaps.empty()) {
      filled[i] = pipeline::interpolate_gaps(values, gap_plan.gaps);
      pieces[i].emplace_back(filled[i]);
    } else if (!gap_plan.pieces.empty()) {
      for (const pipeline::SampleRange& r : gap_plan.pieces) {
        pieces[i].push_back(std::span<const double>(values).subspan(r.begin, r.size()));
      }
    } else {
      pieces[i].emplace_back(values);
    }
  }

  // Axes in parallel: each worker takes the next axis (one thread per axis; the bootstrap of
  // an axis runs in that thread, so the total never exceeds --threads). Each axis's result
  // depends only on its data and index (seeded per axis), not on the thread that ran it.
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = std::min<unsigned>(settings.threads == 0 ? hardware : settings.threads,
                                              static_cast<unsigned>(channels.size()));
  std::vector<std::optional<pipeline::AxisAnalysis>> results(channels.size());
  std::vector<std::exception_ptr> errors(channels.size());
  std::atomic<std::size_t> next{0};
  ChannelProgress progress(channels.size(), options, feedback);
  const auto worker = [&] {
    for (std::size_t i = next++; i < channels.size(); i = next++) {
      const auto [index, channel] = channels[i];
      try {
        pipeline::AxisAnalysisOptions channel_options = options;
        channel_options.progress = progress.callback(i);
        results[i] = pipeline::analyze_axis_pieces(channel->name, index < 3, pieces[i], tau0_s,
                                                   static_cast<int>(index), channel_options);
      } catch (...) {
        errors[i] = std::current_exception();
      }
      progress.channel_finished();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (std::size_t i = 0; i < channels.size(); ++i) {
    if (!errors[i]) continue;
    // The axis analysis names the channel; the user also needs the file.
    try {
      std::rethrow_exception(errors[i]);
    } catch (const AnalysisError& e) {
      throw AnalysisError(source + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(source + ": " + e.what());
    }
  }

  AnalysisResult result;
  result.tau0_s = tau0_s;
  models::NoiseModel& model = result.model;
  model.source = source;
  model.sensor_name = std::filesystem::path(source).filename().string();
  model.sample_rate_hz = 1.0 / tau0_s;
  model.samples = gap_plan.samples;
  model.duration_s = static_cast<double>(model.samples) * tau0_s;
  model.confidence = settings.confidence;
  model.data_quality = quality_findings(recording.report);
  if (!gap_plan.note.empty()) model.data_quality.push_back(gap_plan.note);
  for (auto& r : results) {
    model.axes.push_back(r->model);
    result.axes.push_back(std::move(*r));
  }
  return result;
}

}  // namespace

AnalysisResult analyze_recording(const pipeline::Recording& recording, const std::string& source,
                                 const AnalysisSettings& settings,
                                 const AnalysisFeedback& feedback) {
  return analyze(recording, source, settings, feedback, nullptr);
}

AnalysisResult analyze_recording_freeing_time_stamps(pipeline::Recording& recording,
                                                     const std::string& source,
                                                     const AnalysisSettings& settings,
                                                     const AnalysisFeedback& feedback) {
  return analyze(recording, source, settings, feedback, &recording.time_s);
}

}  // namespace imunoise::tools
