/// @file
/// @brief Typed exceptions of imunoise. Libraries throw them; the CLI catches them once,
/// prints `what()` on one line and exits non-zero.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace imunoise {

/// Bad user input: a file, a flag, a config key. The message names where and what.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A request the data cannot satisfy (e.g. too few samples for the requested tau).
class AnalysisError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A caller bug: a precondition of a library function that valid user input can never break
/// (sizes that must agree, a function called twice, an argument outside its documented range
/// that the caller was required to check). Not a user error: the CLI reports it as an internal
/// error. Bad user input is InputError; data that cannot answer is AnalysisError.
class ContractViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Formats "FILE:LINE:COL: MESSAGE" (line and column 1-based; 0 means "not applicable").
inline std::string located_message(const std::string& file, std::int64_t line, std::int64_t column,
                                   const std::string& message) {
  // Built with append() only: GCC 12 raises a false -Wrestrict on `":" + std::to_string(…)`.
  std::string out = file;
  if (line > 0) {
    out.append(":").append(std::to_string(line));
    if (column > 0) out.append(":").append(std::to_string(column));
  }
  out.append(": ").append(message);
  return out;
}

/// Always-on check for user-facing preconditions (not compiled out like assert).
/// For a caller's contract use IMUNOISE_EXPECT.
#define IMUNOISE_CHECK(cond, ExceptionType, message) \
  do {                                               \
    if (!(cond)) throw ExceptionType(message);       \
  } while (false)

/// Always-on check of a caller's contract: throws ContractViolation(message) when COND fails.
#define IMUNOISE_EXPECT(cond, message)                         \
  do {                                                         \
    if (!(cond)) throw ::imunoise::ContractViolation(message); \
  } while (false)

}  // namespace imunoise
