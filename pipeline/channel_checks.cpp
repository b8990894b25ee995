/// @file
/// @brief The checks of one channel (analyze_channel) and of several in parallel
/// (analyze_channels): pass 1 of lsb_estimate_internal.h, then pass 2 (Σ(v − mean)², saturation
/// runs, full-scale samples) with the quantization step's scan for an off-grid step riding along.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "common/parallel_for.h"
#include "pipeline/lsb_estimate_internal.h"
#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_checks_internal.h"

namespace imunoise::pipeline {

using namespace detail;  // the lanes, pass 1 and the LSB search

namespace {

/// What pass 2 compares the samples with. A sample outside (quiet_lo, quiet_hi) makes its
/// block "loud": the run and full-scale scan has work there (see analyze_channel).
struct ChannelMarks {
  double mean, quiet_lo, quiet_hi;
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // see sampling_checks_internal.h

/// Pass 2 over the whole blocks from I (a multiple of kLanes, ≥ kLanes) on: adds Σ(v − mean)²
/// of them to the lanes SUM_SQ, up to the first loud block (not added). Returns that block's
/// start, or the first i with i + kBlock > n. With kGrid, a step that fails GRID also makes its
/// block loud: the offender scan of estimate_lsb rides along.
template <class D, bool kGrid>
[[gnu::always_inline]] inline std::size_t channel_blocks_of(const double* v, std::size_t i,
                                                            std::size_t n, const ChannelMarks& k,
                                                            const GridTest* grid,
                                                            double (&sum_sq)[kLanes]) {
  D sum[kGroups<D>];
  std::memcpy(sum, sum_sq, sizeof sum);
  const double mean = k.mean, quiet_lo = k.quiet_lo, quiet_hi = k.quiet_hi;
  for (; i + kBlock <= n; i += kBlock) {
    MaskOf<D> quiet = ~MaskOf<D>{};
    for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
      const D x = load<D>(v + j);
      quiet &= (x > quiet_lo) & (x < quiet_hi);
      if (kGrid) quiet &= ~off_grid(vabs(x - load<D>(v + j - 1)), *grid);
    }
    if (any(~quiet)) break;
    for (std::size_t j = i; j < i + kBlock; j += kLanes) {
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const D dev = load<D>(v + j + g * kWidth<D>) - mean;
        sum[g] += dev * dev;
      }
    }
  }
  std::memcpy(sum_sq, sum, sizeof sum);
  return i;
}

#ifdef IMUNOISE_SAMPLING_AVX2
__attribute__((target("avx2"))) std::size_t channel_blocks_avx2(const double* v, std::size_t i,
                                                                std::size_t n,
                                                                const ChannelMarks& k,
                                                                const GridTest* grid,
                                                                double (&sum_sq)[kLanes]) {
  return grid ? channel_blocks_of<D4, true>(v, i, n, k, grid, sum_sq)
              : channel_blocks_of<D4, false>(v, i, n, k, grid, sum_sq);
}
#endif

#pragma GCC diagnostic pop

std::size_t channel_blocks(const double* v, std::size_t i, std::size_t n, const ChannelMarks& k,
                           const GridTest* grid, double (&sum_sq)[kLanes]) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return channel_blocks_avx2(v, i, n, k, grid, sum_sq);
#endif
  return grid ? channel_blocks_of<D2, true>(v, i, n, k, grid, sum_sq)
              : channel_blocks_of<D2, false>(v, i, n, k, grid, sum_sq);
}

}  // namespace

std::vector<ChannelReport> analyze_channels(std::span<const ChannelSamples> channels,
                                            const SamplingOptions& options, unsigned threads) {
  std::vector<ChannelReport> reports(channels.size());
  parallel_for(channels.size(), threads,
               [&](std::size_t i) { reports[i] = analyze_channel(channels[i], options); });
  return reports;
}

ChannelReport analyze_channel(const ChannelSamples& channel, const SamplingOptions& options) {
  ChannelReport r;
  r.name = std::string(channel.name);
  r.unit = std::string(channel.unit);
  r.full_scale = channel.full_scale;
  const auto v = channel.values;
  const std::size_t n = v.size();
  if (n == 0) return r;

  // Pass 1: extremes, Σ and the steps (see extremes).
  const Extremes e = extremes(v);
  const double lo = e.lo, hi = e.hi;
  r.min = lo;
  r.max = hi;
  r.mean = e.sum / static_cast<double>(n);
  r.constant = lo == hi;

  // The quantization step needs pass 1 only, up to its first scan of all steps for one off
  // the grid q it found (pending): that scan rides along in pass 2.
  std::optional<LsbSearch> lsb;
  if (n >= 3) {
    const LsbBounds bounds = lsb_bounds(lo, hi);
    if (bounds.usable) lsb.emplace(v, bounds, steps_above(v, e, bounds.noise_floor));
  }
  std::optional<GridTest> grid;
  if (lsb && lsb->pending()) grid = grid_test(lsb->noise_floor(), *lsb->pending(), lsb->range());
  bool searching = grid.has_value();
  double offender = 0.0;  // the first step off the grid
  const auto check_step = [&](std::size_t i) {
    if (!searching || i == 0) return;
    offender = offending_step(v, i, grid->noise_floor, grid->q);
    searching = offender == 0.0;
  };

  // Pass 2: Σ(v − mean)² (sample i in lane i mod kLanes, then lane_sum) and the scan for
  // saturation runs and full-scale samples.
  std::size_t run_start = 0;
  const auto close_run = [&](std::size_t end) {  // run is [run_start, end)
    const auto len = static_cast<std::int64_t>(end - run_start);
    const double value = v[run_start];
    if (!r.constant && len >= options.saturation_min_run && (value == lo || value == hi)) {
      if (r.saturation_runs++ == 0) r.first_saturation = locate(run_start, options);
      r.saturated_samples += len;
      r.longest_saturation_run = std::max(r.longest_saturation_run, len);
    }
  };
  const auto exact = [&](std::size_t i) {
    if (i > 0 && v[i] != v[run_start]) {
      close_run(i);
      run_start = i;
    }
    if (channel.full_scale && std::fabs(v[i]) >= *channel.full_scale) {
      if (r.beyond_full_scale++ == 0) r.first_beyond_full_scale = locate(i, options);
    }
  };
  // The scan has nothing to do at a "quiet" sample: one that is no extreme (runs count only
  // at the extremes, and none in a constant channel), so lo < x < hi, and below full scale,
  // so −fs < x < fs. A full scale that no sample can be below (≤ 0, NaN) leaves none quiet.
  ChannelMarks marks{r.mean, r.constant ? -kInf : lo, r.constant ? kInf : hi};
  if (channel.full_scale) {
    const double fs = *channel.full_scale;
    marks.quiet_lo = fs > 0.0 ? std::max(marks.quiet_lo, -fs) : kInf;
    marks.quiet_hi = std::min(marks.quiet_hi, fs);
  }
  double sum_sq[kLanes] = {};
  const auto exact_with_sum = [&](std::size_t i) {
    const double dev = v[i] - r.mean;
    sum_sq[i % kLanes] += dev * dev;
    exact(i);
    check_step(i);
  };
  std::size_t i = 0;
  for (; i < std::min(n, kLanes); ++i) exact_with_sum(i);  // as in pass 1
  while (i < n) {
    const std::size_t loud =
        channel_blocks(v.data(), i, n, marks, searching ? &*grid : nullptr, sum_sq);
    if (loud > i) {
      // Quiet blocks [i, loud): a run open at i that is at an extreme ends there; the run
      // open at loud − 1 is at no extreme, so where it started does not matter (it will not
      // count).
      close_run(i);
      run_start = loud - 1;
    }
    // The loud block, or the tail.
    for (i = loud; i < std::min(n, loud + kBlock); ++i) exact_with_sum(i);
  }
  close_run(n);
  r.std_dev = n > 1 ? std::sqrt(lane_sum(sum_sq) / static_cast<double>(n - 1)) : 0.0;
  if (lsb) {
    if (grid) lsb->resume(offender);
    while (const std::optional<double> q = lsb->pending()) {  // grids after the first
      lsb->resume(first_offender(v, lsb->noise_floor(), *q, lsb->range()));
    }
    r.lsb = lsb->result();
  }
  return r;
}

// GCC 12 reports -Wpsabi for the D4 functions it compiles after parsing at the last token of
// the file: off for that token only, nothing follows (see sampling_checks_internal.h).
#pragma GCC diagnostic ignored "-Wpsabi"
}  // namespace imunoise::pipeline
