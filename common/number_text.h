/// @file
/// @brief Number → text for messages, file headers and outputs.
#pragma once

#include <charconv>
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

}  // namespace imunoise
