/// @file
/// @brief The sampling report of a recording as text and as sampling_report.json, for
/// `imunoise check`, `analyze` and the report (the checks themselves: pipeline/sampling_checks.h):
/// the JSON, the file's writer and its strict reader, over the one typed pipeline::SamplingReport.
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

/// The report of a JSON object as sampling_report_to_json writes it. Every key the writer writes
/// is required, with its type; the ones it writes as null when empty (first occurrences, `line`,
/// `lsb`, `full_scale`) are optional, null = empty. A real value the writer could not write as a
/// JSON number (NaN, ±inf: nlohmann writes null) reads back as NaN. Every finite double comes
/// back bit for bit: nlohmann writes digits that read back to the same double (Grisu2, at most
/// 17 significant). Keys the writer does not write are ignored.
/// @param[in] j      the object (`file` is checked to be a string, not returned)
/// @param[in] where  names the source in messages (a path)
/// @throws InputError "WHERE: [PLACE: ]key 'X' missing" or "…key 'X' not a number" (not an
/// integer, a boolean, a string, an array, an object…); PLACE is e.g. `channels[2]`.
pipeline::SamplingReport sampling_report_from_json(const nlohmann::ordered_json& j,
                                                   std::string_view where);

/// sampling_report.json read back: the report and the recording it describes.
struct SamplingReportFile {
  pipeline::SamplingReport report;
  std::string source_path;  ///< the `file` key: the recording as the command line named it
};

/// Writes sampling_report.json at PATH: sampling_report_to_json(REPORT, SOURCE_PATH) with indent 2
/// and a final newline, atomically (AtomicOutputFile: PATH keeps its old content on failure).
/// read_sampling_report_json reads it back to the same report, doubles bit for bit.
/// @throws InputError naming PATH when it cannot be written.
void write_sampling_report_json(const std::string& path, const pipeline::SamplingReport& report,
                                std::string_view source_path);

/// Reads sampling_report.json at PATH (`imunoise analyze -o DIR`, `imunoise check --json`).
/// @throws InputError "PATH: cannot open for reading", "PATH: not valid JSON (…)", or a message
/// of sampling_report_from_json naming PATH.
SamplingReportFile read_sampling_report_json(const std::string& path);

}  // namespace imunoise::io
