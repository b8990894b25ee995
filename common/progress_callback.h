/// @file
/// @brief The progress hook of long computations. The pure layers know nothing about
/// terminals: a long computation takes an optional `ProgressCallback` in its options and calls
/// it at coarse granularity (per stage, bootstrap replicate, Monte Carlo run or 1 MiB block of
/// a file — never per sample); the CLI turns the calls into a progress bar (io/terminal_progress_bar.h).
/// A callback never changes a result: the computation does the same arithmetic with or without
/// one.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace imunoise {

/// Called with `done` of `total` work units finished (0 ≤ done ≤ total, total > 0, in the
/// computation's own units, documented where the callback is accepted) and the stage now
/// running: a short static name ("reading", "deviations", "bootstrap", …). It may be called
/// from worker threads, concurrently and slightly out of order (take the largest `done` seen);
/// it must be cheap and must not throw. An empty callback means no progress reporting.
using ProgressCallback =
    std::function<void(std::string_view stage, std::int64_t done, std::int64_t total)>;

/// Calls `progress` when it is set (the one-line guard every caller needs).
inline void report_progress(const ProgressCallback& progress, std::string_view stage,
                            std::int64_t done, std::int64_t total) {
  if (progress) progress(stage, done, total);
}

}  // namespace imunoise
