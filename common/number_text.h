/// @file
/// @brief Number → text for messages, file headers and outputs.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace imunoise {

/// The shortest decimal text that reads back to exactly VALUE (std::to_chars without a
/// precision): the form used in every output file, so a value written is a value reloaded.
inline std::string shortest_number_text(double value) {
  char buffer[32];  // the longest shortest form of a double has 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// VALUE with at most DIGITS significant digits (iostream default float format, e.g. "0.1235",
/// "1.2e-05"): for summaries and status lines a person reads, never for files read back.
inline std::string significant_number_text(double value, int digits = 4) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

/// A duration with a readable unit, for reports and status lines a person reads: "0 s",
/// "47.7 ns", "8.12 us", "8.126 ms", "310.123 s" (printf %g with 3 significant digits in ns
/// and µs, 4 in ms, 6 in s; the unit chosen by |SECONDS|).
inline std::string duration_text(double seconds) {
  const double a = std::fabs(seconds);
  char buffer[64];
  int length = 0;
  if (a == 0.0) return "0 s";
  if (a < 1e-6) {
    length = std::snprintf(buffer, sizeof buffer, "%.3g ns", seconds * 1e9);
  } else if (a < 1e-3) {
    length = std::snprintf(buffer, sizeof buffer, "%.3g us", seconds * 1e6);
  } else if (a < 1.0) {
    length = std::snprintf(buffer, sizeof buffer, "%.4g ms", seconds * 1e3);
  } else {
    length = std::snprintf(buffer, sizeof buffer, "%.6g s", seconds);
  }
  if (length < 0) return {};
  return std::string(buffer,
                     std::min<std::size_t>(static_cast<std::size_t>(length), sizeof buffer - 1));
}

}  // namespace imunoise
