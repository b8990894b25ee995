/// @file
/// @brief Number → text for messages, file headers and outputs.
#pragma once

#include <charconv>
#include <string>

namespace imunoise {

/// The shortest decimal text that reads back to exactly VALUE (std::to_chars without a
/// precision): the form used in every output file, so a value written is a value reloaded.
inline std::string shortest_number_text(double value) {
  char buffer[32];  // the longest shortest form of a double has 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace imunoise
