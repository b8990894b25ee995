/// @file
/// @brief The flattened Stable32 result tables (expected_stable32.csv in each folder of
/// ../shared/data/allantools-stable32; column meanings in its PROVENANCE.md), parsed once for
/// every test that checks against them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/deviation_type.h"

namespace imunoise::test {

/// One row of a Stable32 table of one of the seven basic statistics.
struct Stable32Row {
  std::string source_file;  ///< the table file the row came from, e.g. "phase_dat_oadev.txt"
  analysis::DeviationType type;
  std::int64_t m;        ///< averaging factor (AF)
  double tau_s;          ///< τ = m·τ0
  std::int64_t n_terms;  ///< Stable32 "#" column
  int alpha;             ///< Stable32's noise type for the interval
  double sigma_min;      ///< lower 68.3 % bound (0 when not given)
  double sigma;          ///< the deviation, 5 significant digits
  double sigma_max;      ///< upper 68.3 % bound (0 when not given)
  bool ci_given;
};

/// Stable32's sigma-type wording → statistic ("Overlapping Allan" → oadev); std::nullopt for
/// the statistics imunoise does not compute (MTOTDEV, TTOTDEV, HTOTDEV, Thêo1, MTIE, TIE rms).
std::optional<analysis::DeviationType> stable32_type(const std::string& sigma_type);

/// All rows of the seven basic statistics in CSV (optionally only those of SOURCE_FILE).
std::vector<Stable32Row> load_stable32_rows(const std::filesystem::path& csv,
                                            const std::string& source_file = "");

}  // namespace imunoise::test
