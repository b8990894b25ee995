/// @file
/// @brief Multi-rate Welch PSD straight into log bins (see multirate_psd.h).
#include "analysis/multirate_psd.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "analysis/halfband.h"
#include "analysis/psd_internal.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

/// Level-0 samples taken per step of the stream (checked, moments, then pushed down).
constexpr std::size_t kChunk = 8192;
/// Decimator outputs per call (then pushed to the next level before more are made).
constexpr std::size_t kBatch = 2048;

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

bool is_power_of_two(std::size_t v) { return v != 0 && (v & (v - 1)) == 0; }

/// Mean square of a record about its trend, accumulated chunk by chunk (Chan, Golub & LeVeque
/// 1983 pairwise update of mean, M₂ and the co-moment with the time index), each chunk in
/// cache in two passes: one pass over memory in all, stable like the two-pass formula.
class RecordMoments {
 public:
  /// Adds X[0 … count). Returns false (adding nothing) when a value is not finite.
  bool add(const double* x, std::size_t count) {
    if (count == 0) return true;
    // Eight lanes combined in a fixed tree (vectorised, independent of the vector width).
    constexpr std::size_t kLanes = 8;
    constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
    double sum[kLanes] = {}, squares[kLanes] = {};
    std::uint64_t non_finite = 0;
    const auto first = [&](std::size_t l, double v) {
      sum[l] += v;
      squares[l] += v * v;
      non_finite |=
          static_cast<std::uint64_t>((std::bit_cast<std::uint64_t>(v) & kExponent) == kExponent);
    };
    std::size_t i = 0;
    for (; i + kLanes <= count; i += kLanes) {
      for (std::size_t l = 0; l < kLanes; ++l) first(l, x[i + l]);
    }
    for (; i < count; ++i) first(i % kLanes, x[i]);
    if (non_finite != 0) return false;
    const double nb = static_cast<double>(count);
    const double mean_b = combine(sum) / nb;
    const double centre_b = 0.5 * (nb - 1.0);  // chunk-local time mean
    double m2[kLanes] = {}, co[kLanes] = {};
    const auto second = [&](std::size_t l, std::size_t k) {
      const double r = x[k] - mean_b;
      m2[l] += r * r;
      co[l] += (static_cast<double>(k) - centre_b) * r;
    };
    for (i = 0; i + kLanes <= count; i += kLanes) {
      for (std::size_t l = 0; l < kLanes; ++l) second(l, i + l);
    }
    for (; i < count; ++i) second(i % kLanes, i);
    const double m2_b = combine(m2), c_b = combine(co);
    const double time_b = static_cast<double>(n_) + centre_b;
    squares_ += combine(squares);
    if (n_ == 0) {
      mean_ = mean_b;
      time_ = time_b;
      m2_ = m2_b;
      c_ = c_b;
    } else {
      const double na = static_cast<double>(n_), n = na + nb;
      const double dx = mean_b - mean_, dt = time_b - time_;
      mean_ += dx * nb / n;
      time_ += dt * nb / n;
      m2_ += m2_b + dx * dx * na * nb / n;
      c_ += c_b + dx * dt * na * nb / n;
    }
    n_ += count;
    return true;
  }

  double mean_square(Detrend mode) const {
    const double n = static_cast<double>(n_);
    switch (mode) {
      case Detrend::none:
        return squares_ / n;
      case Detrend::linear: {
        if (n_ < 2) return m2_ / n;
        const double tt = n * (n * n - 1.0) / 12.0;  // Σ(t − t̄)² of consecutive indices
        return std::max(0.0, m2_ - c_ * c_ / tt) / n;
      }
      case Detrend::constant:
      default:
        return m2_ / n;
    }
  }

 private:
  static double combine(double (&lane)[8]) {
    for (std::size_t width = 4; width >= 1; width /= 2) {
      for (std::size_t l = 0; l < width; ++l) lane[l] += lane[l + width];
    }
    return lane[0];
  }

  std::size_t n_ = 0;
  double mean_ = 0.0, time_ = 0.0, m2_ = 0.0, c_ = 0.0, squares_ = 0.0;
};

/// One level of the cascade while a piece streams through it. Level 0 reads the piece in
/// place; deeper levels keep their recent samples in a buffer of L + kBatch.
struct Level {
  std::vector<double> buffer;
  const double* data = nullptr;  // samples [base, base + size) at data[0 … size)
  std::size_t base = 0;          // absolute index of data[0]
  std::size_t size = 0;
  std::size_t next_segment = 0;  // absolute start of the next Welch segment
  std::size_t next_output = 0;   // next decimator output (reads inputs 2k … 2k + N − 1)
  std::size_t segments = 0;
  std::vector<double> power;  // Σ over this piece's segments of |X_j|²
};

/// The decimation cascade of levels 0 … D sharing one segment transform.
class Cascade {
 public:
  Cascade(detail::SegmentTransform& transform, std::size_t deepest)
      : transform_(transform), levels_(deepest + 1) {
    for (std::size_t d = 1; d < levels_.size(); ++d) {
      levels_[d].buffer.assign(transform_.length() + kBatch, 0.0);
    }
    for (Level& v : levels_) v.power.assign(transform_.bins(), 0.0);
  }

  /// Streams PIECE through every level; per level the segment count and Σ|X_j|² restart.
  /// Checks every sample is finite (ContractViolation naming the first that is not).
  void run(std::span<const double> piece) {
    for (std::size_t d = 0; d < levels_.size(); ++d) {
      Level& v = levels_[d];
      v.data = d == 0 ? piece.data() : v.buffer.data();
      v.base = v.size = v.next_segment = v.next_output = v.segments = 0;
      std::fill(v.power.begin(), v.power.end(), 0.0);
    }
    moments_ = RecordMoments{};
    for (std::size_t start = 0; start < piece.size(); start += kChunk) {
      const std::size_t count = std::min(kChunk, piece.size() - start);
      const double* chunk = piece.data() + start;
      if (!moments_.add(chunk, count)) {
        const std::size_t bad = static_cast<std::size_t>(
            std::find_if(chunk, chunk + count, [](double v) { return !std::isfinite(v); }) -
            piece.data());
        throw ContractViolation("welch: sample " + std::to_string(bad) + " is not finite (" +
                                text(piece[bad]) + ")");
      }
      levels_[0].size = start + count;
      advance(0);
    }
  }

  const Level& level(std::size_t d) const { return levels_[d]; }
  const RecordMoments& moments() const { return moments_; }

 private:
  /// Welch segments of level d that are complete, then as many decimated samples as its
  /// inputs allow, each batch pushed through the deeper levels at once.
  void advance(std::size_t d) {
    Level& v = levels_[d];
    const std::size_t length = transform_.length(), step = transform_.step();
    const std::size_t end = v.base + v.size;
    while (v.next_segment + length <= end) {
      transform_.add_segment(v.data + (v.next_segment - v.base), v.power.data());
      ++v.segments;
      v.next_segment += step;
    }
    if (d + 1 == levels_.size() || end < kHalfbandTaps) return;
    Level& w = levels_[d + 1];
    const std::size_t outputs_end = (end - kHalfbandTaps) / 2 + 1;
    while (v.next_output < outputs_end) {
      const std::size_t count = std::min(kBatch, outputs_end - v.next_output);
      make_room(d + 1, count);
      const std::size_t first = 2 * v.next_output;
      halfband_decimate({v.data + (first - v.base), 2 * (count - 1) + kHalfbandTaps},
                        {w.buffer.data() + w.size, count});
      w.size += count;
      v.next_output += count;
      advance(d + 1);
    }
  }

  /// Drops the samples of level e that neither its next segment nor its decimator still
  /// needs when COUNT more would not fit (what remains is < L: see advance()).
  void make_room(std::size_t e, std::size_t count) {
    Level& w = levels_[e];
    if (w.size + count <= w.buffer.size()) return;
    std::size_t keep = w.next_segment;
    if (e + 1 < levels_.size()) keep = std::min(keep, 2 * w.next_output);
    const std::size_t drop = keep - w.base;
    std::memmove(w.buffer.data(), w.buffer.data() + drop, (w.size - drop) * sizeof(double));
    w.base = keep;
    w.size -= drop;
    IMUNOISE_EXPECT(w.size + count <= w.buffer.size(), "multirate_psd: level buffer overflow");
  }

  detail::SegmentTransform& transform_;
  std::vector<Level> levels_;
  RecordMoments moments_;
};

/// The spectrum of one level pooled over pieces: with one piece its own density and power
/// covariance, with several Σ K_k·S_k and Σ K_k·g_k until finish() divides by K = Σ K_k
/// (pooled_welch_psd's arithmetic, so one level gives its numbers bit for bit).
struct LevelSpectrum {
  std::size_t segments = 0;
  std::size_t pieces = 0;
  std::vector<double> density;
  std::vector<double> covariance;

  void add(const Level& v, detail::SegmentTransform& t, double level_rate_hz) {
    if (v.segments == 0) return;
    const std::size_t bins = t.bins();
    std::vector<double> d(bins);
    // theory.md §5.1: P(f_j) = c_j |Σ w_n x_n e^{−2πijn/L}|² / (f_s Σ w_n²), averaged over K.
    const double scale =
        1.0 / (level_rate_hz * t.window_energy() * static_cast<double>(v.segments));
    for (std::size_t j = 0; j < bins; ++j) {
      d[j] = (detail::is_real_bin(j, t.length()) ? 1.0 : 2.0) * scale * v.power[j];
    }
    std::vector<double> g = t.power_covariance(v.segments);
    if (pieces == 0) {
      density = std::move(d);
      covariance = std::move(g);
    } else {
      if (pieces == 1) {
        const double k = static_cast<double>(segments);
        for (std::size_t j = 0; j < bins; ++j) {
          density[j] = 0.0 + k * density[j];
          covariance[j] = 0.0 + k * covariance[j];
        }
      }
      const double k = static_cast<double>(v.segments);
      for (std::size_t j = 0; j < bins; ++j) {
        density[j] += k * d[j];
        covariance[j] += k * g[j];
      }
    }
    segments += v.segments;
    ++pieces;
  }

  void finish() {
    if (pieces < 2) return;
    const double k_total = static_cast<double>(segments);
    for (std::size_t j = 0; j < density.size(); ++j) {
      density[j] /= k_total;
      covariance[j] /= k_total;
    }
  }
};

/// The log bin of frequency F: ⌊b·log10 f⌋, exactly as log_bin() (shared edges).
double bin_of(double f, double b) { return std::floor(b * std::log10(f) + 1e-9); }

/// Appends to OUT the log bins of level spectrum S (raw spacing DF, raw bins 1 … last) whose
/// key lies in [key_low, key_high), with log_bin()'s arithmetic; adds S₁·Δf of their raw bins
/// to out.integrated_power.
void bin_level(const LevelSpectrum& s, std::size_t length, double df, std::size_t last, double b,
               double key_low, double key_high, Spectrum& out) {
  const detail::PowerCovariance cov{s.covariance, length};
  std::size_t j = 1;
  while (j <= last) {
    const double key = bin_of(static_cast<double>(j) * df, b);
    std::size_t end = j;
    double power = 0.0, log_f = 0.0;
    while (end <= last && bin_of(static_cast<double>(end) * df, b) == key) {
      power += s.density[end];
      log_f += std::log(static_cast<double>(end) * df);
      ++end;
    }
    if (key >= key_low && key < key_high) {
      const std::size_t count = end - j;
      // The Nyquist raw bin (c = 1) holds half the density over half the width: it counts as
      // half a bin, so that the mean is unbiased (log_bin()'s plain mean reads 1/(2·count)
      // low there, which matters when the top bin holds few raw bins).
      const bool nyquist = length % 2 == 0 && end - 1 == length / 2;
      out.frequency_hz.push_back(count == 1 ? static_cast<double>(j) * df
                                            : std::exp(log_f / static_cast<double>(count)));
      out.density.push_back(power / (static_cast<double>(count) - (nyquist ? 0.5 : 0.0)));
      out.dof.push_back(detail::averaged_dof(cov, s.segments, j, end - 1));
      out.first_raw_bin.push_back(j);
      out.raw_bins.push_back(count);
      out.bin_resolution_hz.push_back(df);
      for (std::size_t k = j; k < end; ++k) out.integrated_power += s.density[k] * df;
    }
    j = end;
  }
}

std::size_t deepest_length(std::size_t longest, const MultirateOptions& options) {
  if (options.welch.segment_length != 0) return options.welch.segment_length;
  IMUNOISE_EXPECT(longest >= 16, "welch: record of " + std::to_string(longest) +
                                     " samples is too short (automatic segment length needs "
                                     ">= 16)");
  return automatic_segment_length(longest);
}

Spectrum estimate(std::span<const std::span<const double>> pieces, double sample_rate_hz,
                  const MultirateOptions& options, std::size_t* pieces_used) {
  IMUNOISE_EXPECT(
      std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0,
      "welch: sample rate must be finite and > 0 (got " + text(sample_rate_hz) + " Hz)");
  std::size_t longest = 0;
  for (const auto& p : pieces) longest = std::max(longest, p.size());
  const MultiratePlan plan = multirate_plan(longest, options);
  const std::size_t length = plan.segment_length, deepest = plan.deepest_level;
  detail::SegmentTransform transform(length, options.welch);

  Cascade cascade(transform, deepest);
  std::vector<LevelSpectrum> levels(deepest + 1);
  std::size_t used = 0, used_samples = 0;
  double weighted_variance = 0.0;
  for (const auto& p : pieces) {
    if (p.size() < length) continue;
    cascade.run(p);
    for (std::size_t d = 0; d <= deepest; ++d) {
      const double rate = sample_rate_hz / static_cast<double>(std::size_t{1} << d);
      levels[d].add(cascade.level(d), transform, rate);
    }
    weighted_variance +=
        static_cast<double>(p.size()) * cascade.moments().mean_square(options.welch.detrend);
    used_samples += p.size();
    ++used;
  }
  if (pieces_used != nullptr) *pieces_used = used;
  IMUNOISE_EXPECT(used > 0, "welch: no piece is as long as one segment of " +
                                std::to_string(length) + " samples");
  IMUNOISE_EXPECT(levels[deepest].segments > 0,
                  "multirate_psd: the longest piece (" + std::to_string(longest) +
                      " samples) is shorter than one segment of " + std::to_string(length) +
                      " samples at level " + std::to_string(deepest) +
                      " (L0 = " + std::to_string(length << deepest) + ")");
  for (LevelSpectrum& s : levels) s.finish();

  Spectrum out;
  out.segment_length = length;
  out.segments = levels[deepest].segments;
  out.sample_rate_hz = sample_rate_hz;
  out.fft_plan_from_wisdom = transform.from_wisdom();
  out.resolution_hz = sample_rate_hz / static_cast<double>(length << deepest);
  out.sample_variance = weighted_variance / static_cast<double>(used_samples);
  // The deepest level's DC bin is part of the record's power, as in Welch's Parseval sum.
  out.integrated_power = levels[deepest].density[0] * out.resolution_hz;
  const double b = static_cast<double>(options.bins_per_decade);
  const std::size_t usable = length / 4 - 2;  // J: main lobe inside the passband f_d/4
  double key_low = -std::numeric_limits<double>::infinity();
  for (std::size_t d = deepest + 1; d-- > 0;) {
    const double df = sample_rate_hz / static_cast<double>(length << d);
    const std::size_t last = d == 0 ? length / 2 : usable;
    const double key_high = d == 0 ? std::numeric_limits<double>::infinity()
                                   : bin_of(static_cast<double>(usable + 1) * df, b);
    bin_level(levels[d], length, df, last, b, key_low, key_high, out);
    key_low = std::max(key_low, key_high);
  }
  return out;
}

}  // namespace

MultiratePlan multirate_plan(std::size_t samples, const MultirateOptions& options) {
  const std::size_t level = options.level_segment_length;
  IMUNOISE_EXPECT(is_power_of_two(level) && level >= 256,
                  "multirate_psd: level_segment_length must be a power of two >= 256 (got " +
                      std::to_string(level) + ")");
  IMUNOISE_EXPECT(options.bins_per_decade >= 1,
                  "multirate_psd: bins_per_decade must be >= 1 (got " +
                      std::to_string(options.bins_per_decade) + ")");
  detail::check_options(options.welch);
  const std::size_t l0 = deepest_length(samples, options);
  MultiratePlan plan;
  if (l0 <= level) {
    plan.segment_length = l0;
    return plan;
  }
  plan.segment_length = level;
  while ((level << plan.deepest_level) < l0) ++plan.deepest_level;
  IMUNOISE_EXPECT((level << plan.deepest_level) == l0,
                  "multirate_psd: L0 = " + std::to_string(l0) + " must be level_segment_length (" +
                      std::to_string(level) + ") times a power of two");
  return plan;
}

Spectrum multirate_psd(std::span<const double> x, double sample_rate_hz,
                       const MultirateOptions& options) {
  const std::span<const double> whole[] = {x};
  const MultiratePlan plan = multirate_plan(x.size(), options);
  IMUNOISE_EXPECT(x.size() >= plan.segment_length, "welch: record of " + std::to_string(x.size()) +
                                                       " samples is shorter than one segment of " +
                                                       std::to_string(plan.segment_length));
  return estimate(whole, sample_rate_hz, options, nullptr);
}

Spectrum pooled_multirate_psd(std::span<const std::span<const double>> pieces,
                              double sample_rate_hz, const MultirateOptions& options,
                              std::size_t* pieces_used) {
  return estimate(pieces, sample_rate_hz, options, pieces_used);
}

}  // namespace imunoise::analysis
