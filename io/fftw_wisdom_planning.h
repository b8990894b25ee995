/// @file
/// @brief Measuring FFTW r2c plans into the process's wisdom (what `imunoise fftw-wisdom`
/// saves with io/fftw_wisdom.h), and timing one transform with the measured plan against the
/// FFTW_ESTIMATE plan analysis::WelchEstimator makes without wisdom. Planning holds
/// common/fftw_planner_lock.h's mutex.
#pragma once

#include <cstddef>

namespace imunoise::io {

/// Rigour of the planner search (FFTW_MEASURE or FFTW_PATIENT).
enum class PlannerEffort { kMeasure, kPatient };

/// What planning one length gave.
struct LengthPlanResult {
  double planning_s = 0.0;     ///< wall time of the planner search [s]; 0 when already known
  bool already_known = false;  ///< the wisdom held a plan of this rigour: nothing was measured
  bool usable = false;         ///< wisdom-only planning (as analyze does it) finds a plan
  double wisdom_s = 0.0;       ///< one transform with the wisdom plan [s] (median of 5 batches)
  double estimate_s = 0.0;     ///< one transform with the FFTW_ESTIMATE plan [s] (median)
};

/// Plans the r2c transform of LENGTH (2 ≤ LENGTH ≤ INT_MAX) with EFFORT into the process's
/// wisdom unless the wisdom already covers it, the search stopped after TIME_LIMIT_S when > 0
/// (an interrupted search leaves no reusable wisdom: `usable` is then false). Then times one
/// transform with that plan and with the FFTW_ESTIMATE plan (made with the wisdom set aside),
/// the two alternating over 5 batches of about 2^20 points each, on deterministic input.
/// @throws AnalysisError "fftw-wisdom: FFTW could not plan a transform of length L";
/// ContractViolation for a LENGTH out of range.
LengthPlanResult plan_fft_length(std::size_t length, PlannerEffort effort, double time_limit_s);

}  // namespace imunoise::io
