/// @file
/// @brief plan.csv, the result file of `imunoise plan`: its writer and its reader over one
/// typed pipeline::RecordingPlan. One row per fact, the kind in the first column:
///   expected     — per axis, table duration and term: present, identified and the expected
///                  relative half-width of the 95 % interval (`inf` when not identified);
///   identify     — per axis and term the model has: the shortest duration that identifies it;
///   target       — per axis and targeted term: the shortest duration meeting the target;
///   goal         — per target (axis `all`): the term and its target_percent;
///   all_targets  — one row (axis and term `all`): the shortest recording meeting every target.
/// Columns (units in the names): kind, axis, term (Q N B K R), rate_hz, duration_s, present,
/// identified, relative_halfwidth_percent, target_percent; a cell that does not apply is
/// empty; durations beyond the searched range are `inf`. Numbers are written so that they
/// read back to the same double. Writes are atomic (io/atomic_output.h).
#pragma once

#include <string>

#include "pipeline/recording_plan.h"

namespace imunoise::io {

/// The text of plan.csv for PLAN.
std::string format_plan_csv(const pipeline::RecordingPlan& plan);

/// Writes PLAN to PATH atomically. Throws InputError when PATH cannot be written.
void write_plan_csv(const pipeline::RecordingPlan& plan, const std::string& path);

/// Reads plan.csv. Throws InputError "PATH:LINE: problem" for a missing column, a bad kind,
/// axis, term or number, or a row that contradicts the table.
pipeline::RecordingPlan read_plan_csv(const std::string& path);

/// As read_plan_csv from TEXT; SOURCE_NAME stands for the file name in messages.
pipeline::RecordingPlan parse_plan_csv(const std::string& text, const std::string& source_name);

}  // namespace imunoise::io
