#include "pipeline/gap_policy.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/sampling_gap.h"

namespace imunoise::pipeline {

namespace {

/// "SETTING POLICY", e.g. "--gaps split".
std::string setting_with(std::string_view setting, std::string_view policy) {
  std::string out(setting);
  out.append(" ").append(policy);
  return out;
}

}  // namespace

GapPolicy parse_gap_policy(std::string_view text, std::string_view setting) {
  if (text == "refuse") return GapPolicy::refuse;
  if (text == "split") return GapPolicy::split;
  if (text == "interpolate") return GapPolicy::interpolate;
  std::string message(setting);
  message.append(": expected refuse, split or interpolate, got '").append(text).append("'");
  throw InputError(message);
}

std::vector<TimeGap> find_time_gaps(std::span<const double> time_s, double period_s,
                                    double gap_factor) {
  IMUNOISE_EXPECT(period_s > 0.0 && std::isfinite(period_s),
                  "find_time_gaps: the sample period must be positive");
  std::vector<TimeGap> gaps;
  const double limit = gap_factor * period_s;
  for (std::size_t i = 1; i < time_s.size(); ++i) {
    const double d = time_s[i] - time_s[i - 1];
    if (!(d > limit)) continue;  // also skips NaN intervals
    gaps.push_back({i, time_s[i - 1] - time_s[0], d, missing_samples_in_gap(d, period_s)});
  }
  return gaps;
}

GapSplit split_at_gaps(std::size_t n, std::span<const TimeGap> gaps, std::size_t min_piece) {
  GapSplit out;
  std::size_t begin = 0;
  const auto close = [&](std::size_t end) {
    const SampleRange piece{begin, end};
    if (piece.size() >= min_piece && piece.size() > 0) {
      out.pieces.push_back(piece);
    } else {
      ++out.dropped_pieces;
      out.dropped_samples += piece.size();
    }
    begin = end;
  };
  for (const TimeGap& g : gaps) {
    IMUNOISE_EXPECT(g.after > begin && g.after < n,
                    "split_at_gaps: gaps must be in time order inside the record");
    close(g.after);
  }
  close(n);
  return out;
}

std::int64_t max_interpolated_gap(std::size_t n) {
  return std::min<std::int64_t>(1000,
                                std::max<std::int64_t>(1, static_cast<std::int64_t>(n / 100)));
}

std::vector<double> interpolate_gaps(std::span<const double> values,
                                     std::span<const TimeGap> gaps) {
  std::int64_t added = 0;
  for (const TimeGap& g : gaps) added += g.missing;
  std::vector<double> out;
  out.reserve(values.size() + static_cast<std::size_t>(added));
  std::size_t next = 0;  // first sample of VALUES not yet copied
  for (const TimeGap& g : gaps) {
    IMUNOISE_EXPECT(g.after >= 1 && g.after < values.size() && g.after >= next,
                    "interpolate_gaps: gaps must be in time order inside the record");
    out.insert(out.end(), values.begin() + static_cast<std::ptrdiff_t>(next),
               values.begin() + static_cast<std::ptrdiff_t>(g.after));
    const double a = values[g.after - 1];
    const double b = values[g.after];
    const double steps = static_cast<double>(g.missing + 1);
    const double step = b - a;
    for (std::int64_t j = 1; j <= g.missing; ++j) {
      const double t = static_cast<double>(j) / steps;
      // a + (b − a)·t is exact at equal neighbours (a constant channel stays constant); near
      // the float limits b − a can overflow, and (1 − t)·a + t·b cannot.
      out.push_back(std::isfinite(step) ? a + step * t : (1.0 - t) * a + t * b);
    }
    next = g.after;
  }
  out.insert(out.end(), values.begin() + static_cast<std::ptrdiff_t>(next), values.end());
  return out;
}

std::string gap_refusal_message(const std::string& source, const TimingReport& timing,
                                std::string_view setting) {
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
      .append(" samples missing; the analysis needs uniformly spaced samples: use ")
      .append(setting_with(setting, "split"))
      .append(" (pool the gap-free pieces) or ")
      .append(setting_with(setting, "interpolate"))
      .append(" (fill linearly), or fix the recording");
  const std::int64_t line =
      timing.first_gap && timing.first_gap->line ? *timing.first_gap->line : 0;
  return located_message(source, line, 0, what);
}

GapPlan plan_gaps(const Recording& recording, const std::string& source, GapPolicy policy,
                  bool bootstrap, std::string_view setting) {
  GapPlan plan;
  plan.policy = policy;
  const std::size_t n = recording.sample_count();
  plan.samples = static_cast<std::int64_t>(n);
  const TimingReport& timing = recording.report.timing;
  if (timing.gap_count <= 0 || recording.time_s.size() != n || !(timing.median_interval_s > 0.0)) {
    return plan;
  }
  if (policy == GapPolicy::refuse) {
    throw InputError(gap_refusal_message(source, timing, setting));
  }
  plan.gaps = find_time_gaps(recording.time_s, timing.median_interval_s);
  if (plan.gaps.empty()) return plan;
  const std::string count = std::to_string(plan.gaps.size()) + " time-stamp gap(s)";
  const std::string split_setting = setting_with(setting, "split");
  if (policy == GapPolicy::split) {
    const GapSplit split = split_at_gaps(n, plan.gaps, kMinPieceSamples);
    if (split.pieces.empty()) {
      throw AnalysisError(source + ": " + split_setting + ": no gap-free piece has " +
                          std::to_string(kMinPieceSamples) + " samples or more (" + count +
                          " cut " + std::to_string(n) + " samples into " +
                          std::to_string(split.dropped_pieces) + " pieces)");
    }
    plan.pieces = split.pieces;
    plan.samples = 0;
    for (const auto& piece : plan.pieces) plan.samples += static_cast<std::int64_t>(piece.size());
    plan.note = split_setting + ": " + count + "; the curves and the PSD are pooled over " +
                std::to_string(plan.pieces.size()) + " gap-free piece(s) (" +
                std::to_string(plan.samples) + " samples)";
    if (split.dropped_pieces > 0) {
      plan.note += "; " + std::to_string(split.dropped_pieces) + " piece(s) shorter than " +
                   std::to_string(kMinPieceSamples) + " samples dropped (" +
                   std::to_string(split.dropped_samples) + " samples)";
    }
    if (bootstrap) {
      plan.note += "; bootstrap intervals simulate one record of the total length (approximate)";
    }
    return plan;
  }
  // Interpolate: every gap must be short enough for a straight line to be harmless.
  const std::int64_t limit = max_interpolated_gap(n);
  std::int64_t filled = 0;
  for (const TimeGap& g : plan.gaps) {
    if (g.missing > limit) {
      std::string at = "sample " + std::to_string(g.after);
      if (recording.report.timing.first_gap && recording.report.timing.first_gap->line &&
          recording.report.timing.first_gap->index == static_cast<std::int64_t>(g.after)) {
        at.append(", line ").append(std::to_string(*recording.report.timing.first_gap->line));
      }
      throw InputError(source + ": " + setting_with(setting, "interpolate") + ": the gap before " +
                       at + " (t = " + significant_number_text(g.start_s, 9) + " s, " +
                       significant_number_text(g.length_s) + " s long) lacks " +
                       std::to_string(g.missing) + " samples, more than interpolation may fill (" +
                       std::to_string(limit) + ": 1 % of the record, at most 1000); use " +
                       split_setting);
    }
    filled += g.missing;
  }
  plan.samples += filled;
  plan.note = setting_with(setting, "interpolate") + ": " + count + " filled with " +
              std::to_string(filled) +
              " linearly interpolated sample(s) per channel (noise-free, so the shortest tau "
              "read slightly low)";
  return plan;
}

}  // namespace imunoise::pipeline
