/// @file
/// @brief What a command reports of its own progress besides the bar: the wall time of each
/// stage (StageTimes, for -v), and the feed of one io/terminal_progress_bar.h bar from
/// channels analysed in parallel (ChannelProgress). Neither changes a result.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/progress_callback.h"
#include "io/terminal_progress_bar.h"

namespace imunoise::io {

/// Wall seconds per named stage, in the order first seen. Thread-safe (add() may come from
/// worker threads; the lock is held only to add a number).
class StageTimes {
 public:
  StageTimes();
  /// Adds `seconds` to `stage`.
  void add(std::string_view stage, double seconds);
  /// Adds the wall time since the previous mark (or construction) to `stage`.
  void mark(std::string_view stage);
  /// Seconds since construction.
  double elapsed_s() const;
  /// "read 0.52 s, deviations 3.1 s" (empty when nothing was added).
  std::string text() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<std::string, double>> stages_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_mark_;
};

/// Feeds one progress bar and the stage times from the channels analysed in parallel: the
/// bar's fraction is the sum of the channels' units over their total, its stage the one
/// reported last. Only atomics on the hot path; the times take a short lock on a stage change.
class ChannelProgress {
 public:
  /// CHANNELS channels of UNITS_PER_CHANNEL progress units each; BAR and CHANNEL_TIMES may be
  /// null (nobody listens).
  ChannelProgress(std::size_t channels, std::int64_t units_per_channel, ProgressBar* bar,
                  StageTimes* channel_times)
      : feedback_{bar, channel_times},
        done_(channels),
        stage_(channels),
        stage_start_(channels),
        units_per_channel_(units_per_channel),
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

  struct Feedback {
    ProgressBar* bar;
    StageTimes* channel_times;
  };
  const Feedback feedback_;
  std::vector<std::atomic<std::int64_t>> done_;
  std::vector<std::string> stage_;  // under times_mutex_
  std::vector<std::chrono::steady_clock::time_point> stage_start_;
  std::mutex times_mutex_;
  const std::int64_t units_per_channel_;
  const std::int64_t channels_;
  std::atomic<std::int64_t> finished_{0};
};

}  // namespace imunoise::io
