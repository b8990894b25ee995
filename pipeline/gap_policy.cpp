#include "pipeline/gap_policy.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/sampling_gap.h"

namespace imunoise::pipeline {

GapPolicy parse_gap_policy(std::string_view text) {
  if (text == "refuse") return GapPolicy::refuse;
  if (text == "split") return GapPolicy::split;
  if (text == "interpolate") return GapPolicy::interpolate;
  std::string message = "--gaps: expected refuse, split or interpolate, got '";
  message.append(text).append("'");
  throw InputError(message);
}

std::vector<TimeGap> find_time_gaps(std::span<const double> time_s, double period_s,
                                    double gap_factor) {
  IMUNOISE_CHECK(period_s > 0.0 && std::isfinite(period_s), InputError,
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
    IMUNOISE_CHECK(g.after > begin && g.after < n, InputError,
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
    IMUNOISE_CHECK(g.after >= 1 && g.after < values.size() && g.after >= next, InputError,
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

}  // namespace imunoise::pipeline
