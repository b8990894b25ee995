/// @file
/// @brief Durations written by people: "2h", "30min", "600s" or "600" (seconds), for flags
/// and config values; the error names what was being read and suggests the spelling that
/// works for the usual slips ("30 min", "5m", "2hours", "500ms").
#pragma once

#include <string>

namespace imunoise::io {

/// Seconds in TEXT ("2h", "30min", "600s", "600"), finite and > 0 (≥ 0 with ALLOW_ZERO).
/// @throws InputError "WHAT: expected a positive number with unit s, min or h (e.g. 2h, 30min,
/// 600s), got 'TEXT'", with a hint for a unit written with a space or misspelt.
double parse_duration_s(const std::string& text, const std::string& what, bool allow_zero = false);

}  // namespace imunoise::io
