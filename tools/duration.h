/// @file
/// @brief Durations on the command line: "2h", "30min", "600s" or "600" (seconds).
#pragma once

#include <string>

namespace imunoise::tools {

/// Seconds in TEXT ("2h", "30min", "600s", "600"), finite and > 0 (≥ 0 with ALLOW_ZERO).
/// @throws InputError "FLAG: expected a positive number with unit s, min or h …, got 'TEXT'".
double parse_duration_s(const std::string& text, const std::string& flag, bool allow_zero = false);

}  // namespace imunoise::tools
