/// @file
/// @brief The verdict of a fitted model, what a reader needs first (issue 23): per sensor an
/// axis × term matrix in datasheet units with intervals, what was identified and what was not,
/// every finding with its cause and remedy (report/finding_remedies.h), grouped over axes, and
/// which `imunoise export --to FORMAT` suits which filter. The report page's first section and
/// the head of `imunoise analyze`'s terminal summary. Pure: a model in, tables and text out.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "common/sensor_kind.h"
#include "models/noise_model.h"
#include "report/finding_remedies.h"
#include "report/html_page.h"

namespace imunoise::report {

/// "verdict-gyro" / "verdict-accel": one row per term (its symbol and datasheet unit), one
/// column per axis of KIND; a cell is "value [low, high]" in datasheet units, "< bound (not
/// identified)" or "not identified". No rows when MODEL has no axis of KIND.
Table verdict_matrix(const models::NoiseModel& model, SensorKind kind);

/// One line per sensor: the terms identified on every axis, on some axes, and on none.
std::vector<std::string> identification_lines(const models::NoiseModel& model);

/// The findings of MODEL explained (explain_model_findings), grouped: the notes of one term not
/// identified on several axes of a sensor become one finding (the remedy of the axis that needs
/// the longest record), and findings equal in text, cause and remedy on several axes one.
std::vector<ExplainedFinding> verdict_findings(const models::NoiseModel& model,
                                               std::string_view model_path);

/// One export guide entry: the consumer (filter or framework) and the command for it.
struct ExportGuideEntry {
  std::string consumer;
  std::string command;
};

/// `imunoise export MODEL_PATH --to FORMAT -o FILE` for every format but native, then
/// `imunoise discretize` for a filter of one's own.
std::vector<ExportGuideEntry> export_guide(std::string_view model_path);

/// "export-guide": the guide as a table (filter, command).
Table export_guide_table(std::string_view model_path);

/// The verdict as plain text for the terminal (every line ends with '\n'): per sensor the
/// matrix (terms down, axes across), the identification lines, the findings with "cause:" and
/// "remedy:" lines, and the export guide in a few lines.
std::string verdict_text(const models::NoiseModel& model, std::string_view model_path);

}  // namespace imunoise::report
