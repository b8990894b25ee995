/// @file
/// @brief Text for XML and HTML documents (the SVG plots and the HTML report share it).
#pragma once

#include <string>
#include <string_view>

namespace imunoise::report {

/// Appends TEXT as XML/HTML character data or double-quoted attribute value: & < > " escaped,
/// tab/CR/LF → space, other control characters dropped, invalid UTF-8 (and U+FFFE/U+FFFF) → U+FFFD.
void append_markup_text(std::string& out, std::string_view text);

}  // namespace imunoise::report
