/// @file
/// @brief The Allan-family statistics imunoise computes, and their names.
#pragma once

#include <optional>
#include <string_view>

namespace imunoise::analysis {

/// Allan-family deviation estimators (definitions: ../shared/docs/theory.md §2, NIST SP 1065).
enum class DeviationType {
  adev,    ///< non-overlapping Allan deviation
  oadev,   ///< overlapping Allan deviation (the project default)
  mdev,    ///< modified Allan deviation
  tdev,    ///< time deviation, τ·MDEV/√3 (phase units)
  hdev,    ///< non-overlapping Hadamard deviation
  ohdev,   ///< overlapping Hadamard deviation
  totdev,  ///< total deviation (SP 1065 doubly reflected)
};

/// Lower-case name used on the command line and in JSON ("oadev").
std::string_view to_string(DeviationType type);

/// Parses the lower-case name; std::nullopt when unknown.
std::optional<DeviationType> parse_deviation_type(std::string_view name);

/// Stable32 stop ratio r: the largest averaging factor is ⌊M/r⌋ for M phase samples
/// (4 for OADEV, MDEV, TDEV, OHDEV; 5 for ADEV, HDEV; 2 for TOTDEV; theory.md §2).
int stop_ratio(DeviationType type);

}  // namespace imunoise::analysis
