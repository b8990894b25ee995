/// @file
/// @brief The native model.yaml (schema v1, docs/model-yaml.md): a models::NoiseModel written
/// as text with SI units named in every key, and read back bit-exactly with located,
/// key-naming errors. Every export reads the model through load_model_yaml().
#pragma once

#include <string>

#include "models/noise_model.h"

namespace imunoise::io {

/// `format:` value and `format_version:` this build writes and reads.
inline constexpr const char* kModelYamlFormat = "imunoise-noise-model";
inline constexpr int kModelYamlVersion = 1;

/// @name Writing
/// @{

/// Text of the native model.yaml for MODEL: deterministic (fixed key order, axes in model
/// order), numbers in shortest round-trip form (std::to_chars), strings double-quoted with
/// escapes, so parse_model_yaml() gives back every field bit for bit.
/// @param[in] model the model; it must satisfy the loading rules of docs/model-yaml.md
///   (finite numbers, coefficients ≥ 0, ci_low ≤ ci_high, unique axis names, …).
/// @throws ContractViolation naming the key path when MODEL breaks a loading rule (a caller
///   bug) — the text is checked by parsing it back, so every text returned here loads.
std::string format_model_yaml(const models::NoiseModel& model);

/// Writes format_model_yaml(MODEL) to PATH through AtomicOutputFile: PATH is replaced only
/// when the whole text is on disk; on any failure it keeps its previous content.
/// @throws ContractViolation as format_model_yaml(); InputError naming PATH on I/O errors.
void write_model_yaml(const models::NoiseModel& model, const std::string& path);

/// @}
/// @name Reading
/// @{

/// Loads the model.yaml at PATH (rules in docs/model-yaml.md).
/// @throws InputError "PATH:LINE:COL: key.path: what (got …)" on any problem: unreadable
///   file, YAML syntax, format/format_version mismatch, unknown key (the accepted ones are
///   listed), missing required key, duplicate key, wrong type, non-finite or negative value,
///   ci_low > ci_high, unknown axis sensor.
models::NoiseModel load_model_yaml(const std::string& path);

/// As load_model_yaml() from TEXT; SOURCE_NAME stands for the file name in messages.
models::NoiseModel parse_model_yaml(const std::string& text, const std::string& source_name);

/// @}

}  // namespace imunoise::io
