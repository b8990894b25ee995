/// @file
/// @brief Shared helpers for the test suite: where the reference data and the CLI binary are.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::test {

/// Folder holding NIST / Stable32 reference data: $IMUNOISE_REFERENCE_DATA, else
/// <source>/../shared/data. std::nullopt when it does not exist.
std::optional<std::filesystem::path> reference_data_dir();

/// Skips the current test (GTEST_SKIP) with a clear message when the reference data is
/// absent; use as: IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
#define IMUNOISE_REQUIRE_REFERENCE_DATA(var)                                                      \
  const auto var##_opt = ::imunoise::test::reference_data_dir();                                  \
  if (!var##_opt) {                                                                               \
    GTEST_SKIP() << "reference data not found: set IMUNOISE_REFERENCE_DATA to the folder "        \
                    "holding nist-sp1065-nbs/ and allantools-stable32/ (default ../shared/data)"; \
  }                                                                                               \
  const std::filesystem::path var = *var##_opt

/// Path of the built `imunoise` binary.
std::string imunoise_binary();

/// A fresh empty temporary directory for one test (removed by the OS/tmp cleaner, not here).
std::filesystem::path make_temp_dir(const std::string& tag);

/// Result of running a shell command: exit code, stdout and stderr.
struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs the imunoise binary with ARGS (a shell-quoted string), capturing both streams.
CommandResult run_imunoise(const std::string& args);

/// The whole file at PATH, byte for byte ("" when it cannot be read).
std::string read_file_bytes(const std::filesystem::path& path);

/// 'PATH' for a POSIX shell command line (paths here never hold a single quote).
std::string quoted_for_shell(const std::filesystem::path& path);

/// Reads a one-number-per-line file, skipping '#' comment and blank lines (test-side reader,
/// independent of io/ so analysis tests do not depend on the production parser).
std::vector<double> read_number_lines(const std::filesystem::path& path);

/// A CSV file as rows of fields (header row first); handles double-quoted fields.
std::vector<std::vector<std::string>> read_csv_rows(const std::filesystem::path& path);

/// The SP 1065 "NBS14" 1000-point fractional-frequency set, built from its published Lehmer
/// generator: n_0 = 1234567890, n_{i+1} = 16807·n_i mod (2^31 − 1), y_i = n_i/(2^31 − 1).
std::vector<double> nbs14_1000_frequency();

/// The SP 1065 9-point frequency set: 892, 809, 823, 798, 671, 644, 883, 903, 677.
std::vector<double> nbs9_frequency();

/// N samples of zero-mean Gaussian white noise of standard deviation SIGMA from
/// std::mt19937_64 seeded with SEED (the same numbers for the same seed on every platform's
/// libstdc++).
std::vector<double> white_noise(std::size_t n, double sigma, std::uint64_t seed);

/// Runs F and expects it to throw E whose what() contains FRAGMENT (a test failure otherwise).
template <class E, class F>
void expect_throw_containing(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception thrown, expected one mentioning '" << fragment << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

/// The what() of the InputError thrown by F; a test failure (and "") when none is thrown.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return {};
}

/// Writes TEXT to PATH (test fixtures).
void write_text(const std::filesystem::path& path, const std::string& text);

}  // namespace imunoise::test
