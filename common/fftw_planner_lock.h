/// @file
/// @brief The one process-wide mutex around FFTW's planner. FFTW's planner (plan creation
/// and destruction) is not thread-safe, while fftw_execute on distinct plans is; every file
/// that makes or destroys plans must hold this same mutex, or two layers planning at once
/// (e.g. the PSD and the power-law noise generator) would race.
#pragma once

#include <mutex>

namespace imunoise {

/// The mutex to hold while creating or destroying any FFTW plan.
inline std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace imunoise
