#include "report/svg_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "report/markup_text.h"
#include "report/svg_style.h"

namespace imunoise::report::svg_detail {
namespace {

/// Number of characters (UTF-8 code points) of TEXT.
std::size_t char_count(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u;
  }));
}

}  // namespace

void append_number(std::string& out, double v) {
  if (!std::isfinite(v)) v = 0.0;
  v = std::clamp(v, -1e9, 1e9);
  char buffer[32];
  char* end = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, 2).ptr;
  while (end[-1] == '0') --end;  // there is always a '.' with precision 2
  if (end[-1] == '.') --end;
  const std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
  out.append(text == "-0" ? "0" : text);
}

void append_text(std::string& out, std::string_view text) { append_markup_text(out, text); }

double text_width(std::string_view text, double font_size) {
  return static_cast<double>(char_count(text)) * kCharWidth * font_size;
}

void attr(std::string& out, std::string_view name, double v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  append_number(out, v);
  out.push_back('"');
}

void attr(std::string& out, std::string_view name, std::string_view v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  append_text(out, v);
  out.push_back('"');
}

void attr_raw(std::string& out, std::string_view name, std::string_view v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  out.append(v);
  out.push_back('"');
}

void path_point(std::string& d, char command, double x, double y) {
  if (!d.empty()) d.push_back(' ');
  if (command != 0) d.push_back(command);
  append_number(d, x);
  d.push_back(' ');
  append_number(d, y);
}

void path_length(std::string& d, char command, double v) {
  d.push_back(' ');
  d.push_back(command);
  append_number(d, v);
}

std::string sanitized_id(std::string_view id) {
  std::string out;
  for (char c : id) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    out.push_back(ok ? c : '_');
  }
  if (out.empty() ||
      !((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z') || out[0] == '_')) {
    out.insert(out.begin(), 'p');
  }
  return out;
}

void append_label_style(std::string& out, std::string_view anchor, std::string_view color) {
  attr(out, "text-anchor", anchor);
  attr(out, "font-size", kSmallFont);
  attr(out, "fill", color);
  out.append(
      " stroke=\"#ffffff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">");
}

}  // namespace imunoise::report::svg_detail
