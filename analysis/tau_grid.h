/// @file
/// @brief Averaging-factor (τ) grids: octave, decade, all, log:N, or an explicit list.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/deviation_type.h"

namespace imunoise::analysis {

/// How the averaging factors m (τ = m·τ0) are chosen (theory.md §2 "τ grids").
struct TauGridSpec {
  enum class Kind {
    octave,        ///< m = 1, 2, 4, 8, …
    decade,        ///< m = 1, 2, 4, 10, 20, 40, 100, … (Stable32 / allantools "decade")
    all,           ///< every m from 1 to the maximum (O(M²) in total: refused for long records)
    log,           ///< per_decade log-spaced points per decade, rounded to integers, de-duplicated
    explicit_list  ///< the factors in `factors`, validated against the record length
  };
  Kind kind = Kind::octave;
  int per_decade = 10;                ///< for Kind::log
  std::vector<std::int64_t> factors;  ///< for Kind::explicit_list (ascending, unique)
};

/// Parses "octave", "decade", "all", "log:N" (1 ≤ N ≤ 1000) or "m1,m2,…" (positive
/// integers). Throws imunoise::InputError with the offending text.
TauGridSpec parse_tau_grid(std::string_view text);

/// Largest averaging factor for TYPE on M phase samples: ⌊M / stop_ratio(type)⌋, and never
/// beyond the last m that still yields one term of the estimator.
std::int64_t max_averaging_factor(DeviationType type, std::int64_t n_phase);

/// Number of terms TYPE sums at averaging factor m on M phase samples (0 when none).
std::int64_t estimator_term_count(DeviationType type, std::int64_t n_phase, std::int64_t m);

/// The averaging factors of SPEC for TYPE on M phase samples, ascending. Throws
/// imunoise::AnalysisError ("too few samples for the requested tau …") when an explicit factor
/// exceeds the maximum, or when the record is too short for even m = 1.
std::vector<std::int64_t> averaging_factors(const TauGridSpec& spec, DeviationType type,
                                            std::int64_t n_phase);

/// Text form of a spec ("octave", "log:10", "1,2,5").
std::string to_string(const TauGridSpec& spec);

}  // namespace imunoise::analysis
