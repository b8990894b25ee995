/// @file
/// @brief The Allan-family statistics imunoise computes, and their names.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace imunoise::analysis {

/// Allan-family deviation estimators (definitions: ../shared/docs/theory.md §2, NIST SP 1065).
enum class DeviationType {
  adev,     ///< non-overlapping Allan deviation
  oadev,    ///< overlapping Allan deviation (the project default)
  mdev,     ///< modified Allan deviation
  tdev,     ///< time deviation, τ·MDEV/√3 (phase units)
  hdev,     ///< non-overlapping Hadamard deviation
  ohdev,    ///< overlapping Hadamard deviation
  totdev,   ///< total deviation (SP 1065 doubly reflected)
  mtotdev,  ///< modified total deviation (SP 1065; O(M·m) per τ)
  ttotdev,  ///< time total deviation, τ·MTOTDEV/√3 (phase units; O(M·m) per τ)
  htotdev,  ///< Hadamard total deviation (SP 1065; O(M·m) per τ)
  theo1,    ///< Thêo1 (SP 1065 eq. 30): even m, τ = 0.75·m·τ0; O(M·m) per τ
};

/// True for the statistics whose cost per τ grows with m (total family, Thêo1).
bool cost_grows_with_m(DeviationType type);

/// τ of averaging factor m: m·τ0, except 0.75·m·τ0 for Thêo1.
double tau_of(DeviationType type, std::int64_t m, double tau0_s);

/// Lower-case name used on the command line and in JSON ("oadev").
std::string_view to_string(DeviationType type);

/// Parses the lower-case name; std::nullopt when unknown.
std::optional<DeviationType> parse_deviation_type(std::string_view name);

/// Stable32 stop ratio r: the largest averaging factor is ⌊M/r⌋ for M phase samples
/// (4 for OADEV, MDEV, TDEV, OHDEV; 5 for ADEV, HDEV; 2 for TOTDEV; theory.md §2; 3 for
/// MTOTDEV, TTOTDEV, HTOTDEV; 1 for Thêo1, whose m may reach M − 1).
int stop_ratio(DeviationType type);

}  // namespace imunoise::analysis
