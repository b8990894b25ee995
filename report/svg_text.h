/// @file
/// @brief SVG text output for the plot writer (internal to report/svg_*): numbers with at most
/// 2 decimals, escaped text and its estimated width, attributes, path-data commands and the
/// text style of labels drawn over the data.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace imunoise::report::svg_detail {

/// Appends pixel coordinate V: at most 2 decimals, trailing zeros dropped, never "-0", "nan"
/// or "inf" (non-finite → 0, clamped to ±1e9).
void append_number(std::string& out, double v);

/// Appends TEXT XML-escaped (append_markup_text).
void append_text(std::string& out, std::string_view text);

/// Estimated width [px] of TEXT in FONT_SIZE: code points × kCharWidth em.
double text_width(std::string_view text, double font_size);

/// @name Attributes: each appends ` NAME="V"`
/// @{
void attr(std::string& out, std::string_view name, double v);            ///< V a coordinate
void attr(std::string& out, std::string_view name, std::string_view v);  ///< V escaped
/// V made by the plot writer (path data, numbers): nothing to escape.
void attr_raw(std::string& out, std::string_view name, std::string_view v);
/// @}

/// @name Path data
/// @{
/// Appends " M X Y" (COMMAND 'M', 'L', …) or " X Y" (COMMAND 0: an implicit line-to after a
/// move) to D, without the leading space when D is empty.
void path_point(std::string& d, char command, double x, double y);
/// Appends " hW", " vH", " VY" etc.: one-coordinate COMMAND with value V.
void path_length(std::string& d, char command, double v);
/// @}

/// ID with characters other than [A-Za-z0-9_-] replaced by '_', prefixed with 'p' unless it
/// starts with a letter or '_' (a valid XML id).
std::string sanitized_id(std::string_view id);

/// Text attributes (up to and including the closing '>' of the start tag) shared by the labels
/// drawn over the data: ANCHOR, the small font, COLOR and a white halo that keeps them
/// readable over lines and the grid.
void append_label_style(std::string& out, std::string_view anchor, std::string_view color);

}  // namespace imunoise::report::svg_detail
