/// @file
/// @brief The sampling report of a recording as text and as sampling_report.json, for
/// `imunoise check`, `analyze` and the report (the checks themselves: pipeline/sampling_checks.h).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

#include "pipeline/sampling_checks.h"

namespace imunoise::io {

/// Human-readable multi-line report.
std::string format_sampling_report(const pipeline::SamplingReport& report,
                                   std::string_view source_path);

/// JSON object (keys in reading order); keys carry units (`rate_hz`, `longest_gap_s`,
/// `jitter_rms_s`), per-channel values are in that channel's `unit` (SI for gyro and accel).
/// First occurrences are {"index": 0-based sample, "line": file line or null}, or null.
nlohmann::ordered_json sampling_report_to_json(const pipeline::SamplingReport& report,
                                               std::string_view source_path);

}  // namespace imunoise::io
