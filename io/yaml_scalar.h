/// @file
/// @brief Text as a YAML scalar, for the writers of the YAML result files (model.yaml,
/// discrete_model.yaml): one quoting rule, so any text a user gives (a path with ':', '#', a
/// quote, a backslash, a leading space or a newline) reads back unchanged.
#pragma once

#include <string>
#include <string_view>

namespace imunoise::io {

/// TEXT as a YAML double-quoted scalar (YAML 1.2 §7.3.1). Quote, backslash and the C0 controls
/// and DEL are escaped (\", \\, \n, \r, \t, \xHH) so the scalar stays on one line; every other
/// byte, UTF-8 included, is copied as is (yaml-cpp reads them back unchanged). An ordinary
/// path comes out as itself between double quotes.
std::string yaml_double_quoted(std::string_view text);

/// Whether TEXT holds a C0 control character or DEL (a byte yaml_double_quoted escapes other
/// than the quote and the backslash): text that cannot stand in a one-line comment as is.
bool has_control_character(std::string_view text);

}  // namespace imunoise::io
