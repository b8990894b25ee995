/// @file
/// @brief The CLI's progress bar: one line on stderr,
/// `analyze: deviations [##########          ]  50%  3/6 channels  0:04`, redrawn in place
/// with '\r' at most ten times a second and ended with '\n' at 100 % by finish(). Only the
/// tools draw it; computations report through common/progress_callback.h callbacks.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>

#include "common/progress_callback.h"

namespace imunoise::io {

/// What one progress line shows.
struct ProgressLine {
  std::string_view label;       ///< the command, e.g. "analyze"
  std::string_view stage;       ///< what runs now, e.g. "deviations" (may be empty)
  std::size_t stage_width = 0;  ///< pad the stage to this many characters (steadier bar)
  std::int64_t done = 0;        ///< the bar and percentage: done of total (clamped)
  std::int64_t total = 0;
  std::int64_t items_done = 0;  ///< "3/6 channels"; left out when items_total <= 0
  std::int64_t items_total = 0;
  std::string_view items_unit;
  double elapsed_s = 0.0;  ///< shown as m:ss (h:mm:ss from an hour)
};

/// The line for `p`, at most `columns` − 1 characters (the last column is left free so a
/// terminal never wraps it). Pure; ASCII only. The bar shrinks first, then the item count is
/// dropped, then the text is cut.
std::string render_progress_line(const ProgressLine& p, int columns);

/// Columns of the terminal on stderr (TIOCGWINSZ), 80 when unknown.
int stderr_columns();

/// A progress bar on stderr for one command. When disabled (stderr not a terminal, or
/// --quiet) every call is a no-op and nothing is ever written. Thread-safe: the counters are
/// atomic, and a thread that finds another one drawing skips its draw instead of waiting, so
/// no computation thread is ever held up by the terminal.
class ProgressBar {
 public:
  ProgressBar(std::string label, bool enabled);
  /// Blanks a bar left unfinished (an exception is on its way, and its message should not
  /// follow a stale "37 %" on the same line).
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool enabled() const { return enabled_; }

  /// The running stage and its fraction done/total; redraws when 0.1 s has passed since the
  /// last draw. A smaller `done` than the last one for the same stage and total is ignored
  /// (reports from several threads may arrive out of order).
  void update(std::string_view stage, std::int64_t done, std::int64_t total);

  /// The "3/6 channels" part (unit: a short plural noun); items_total <= 0 hides it.
  void set_items(std::int64_t items_done, std::int64_t items_total, std::string_view unit);

  /// A ProgressCallback feeding update() (empty when the bar is disabled, so computations
  /// skip even the call). The bar must outlive the callback's use.
  ProgressCallback callback();

  /// Draws the final 100 % line with stage `stage` and ends it with '\n', so the next output
  /// starts on a clean line; nothing if nothing was drawn. Later calls are no-ops.
  void finish(std::string_view stage = "done");

 private:
  void draw(bool final_line);

  const std::string label_;
  const bool enabled_;
  const std::chrono::steady_clock::time_point start_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<std::int64_t> total_{0};
  std::atomic<std::int64_t> items_done_{0};
  std::atomic<std::int64_t> items_total_{0};
  std::atomic<std::int64_t> last_draw_ns_;  ///< steady-clock time of the last draw
  std::atomic<bool> finished_{false};
  std::mutex text_mutex_;  ///< guards stage_ and items_unit_ (short copies only)
  std::string stage_;
  std::string items_unit_;
  std::mutex draw_mutex_;        ///< one drawing thread at a time (try_lock from update)
  std::size_t stage_width_ = 0;  ///< under draw_mutex_
  std::size_t drawn_chars_ = 0;  ///< length of the line on screen; under draw_mutex_
};

}  // namespace imunoise::io
