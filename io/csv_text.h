/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): the text conventions every part of it
/// shares (io/line_source, io/table_layout, io/csv_row_parser, io/csv_chunked_parse): the
/// line limit and the BOM, blanks, comment and blank lines, delimiters, one delimited field,
/// and the bounded rendering of file text in messages.
#pragma once

#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "io/input_config.h"

namespace imunoise::io::csv_detail {

/// Lines of this many bytes or more are refused: not a numeric table (memory stays bounded).
inline constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;
/// UTF-8 byte order mark, skipped at the start of line 1.
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

/// Printable, bounded rendering of file text for messages: binary garbage stays one line.
inline std::string show(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  if (text.size() > kMax) out += "...";
  return out;
}

/// Blanks surround fields; in whitespace mode runs of them separate fields.
inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// The field of a SEP-delimited line that starts at P: [B, E) with blanks trimmed. Returns the
/// separator that ends it, or nullptr when it runs to END.
inline const char* delimited_field(const char* p, const char* end, char sep, const char*& b,
                                   const char*& e) {
  const char* d = static_cast<const char*>(std::memchr(p, sep, static_cast<std::size_t>(end - p)));
  const char* fe = d != nullptr ? d : end;
  b = p;
  while (b != fe && is_blank(*b)) ++b;
  e = fe;
  while (e != b && is_blank(e[-1])) --e;
  return d;
}

/// True when LINE holds something besides blanks and is not a '#' comment.
inline bool is_content(std::string_view line) {
  for (char c : line) {
    if (!is_blank(c)) return c != '#';
  }
  return false;
}

/// The separator character of a resolved delimiter (' ' for whitespace).
inline char delimiter_char(Delimiter d) {
  switch (d) {
    case Delimiter::kComma:
      return ',';
    case Delimiter::kTab:
      return '\t';
    case Delimiter::kSemicolon:
      return ';';
    default:
      return ' ';
  }
}

}  // namespace imunoise::io::csv_detail
