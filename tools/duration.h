/// @file
/// @brief Durations on the command line: io/duration_parser.h's parse_duration_s with the flag
/// as WHAT, e.g. parse_duration_s(text, "--duration").
#pragma once

#include "io/duration_parser.h"

namespace imunoise::tools {

using io::parse_duration_s;

}  // namespace imunoise::tools
