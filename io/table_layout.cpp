/// @file
/// @brief Sniffing a table's layout, and TableLayout's labels (see table_layout.h).
#include "io/table_layout.h"

#include <algorithm>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "io/csv_text.h"
#include "io/decimal_number.h"
#include "io/line_source.h"

namespace imunoise::io {

namespace csv_detail {

namespace {

constexpr std::size_t kSniffBytes = std::size_t{256} << 10;   // enough for the first lines
constexpr std::size_t kMaxSniffBytes = std::size_t{8} << 20;  // long comment preambles
constexpr std::size_t kSniffLines = 64;

[[noreturn]] void fail(const std::string& path, std::int64_t line, std::int64_t column,
                       const std::string& what) {
  throw InputError(located_message(path, line, column, what));
}

/// Calls on_field(index, begin, end) for each field of `line` (trimmed of blanks) and returns
/// the field count. Whitespace mode: runs of blanks separate, leading/trailing ones are ignored.
template <typename OnField>
inline std::size_t for_each_field(std::string_view line, Delimiter delimiter, OnField&& on_field) {
  const char* p = line.data();
  const char* const end = p + line.size();
  std::size_t index = 0;
  if (delimiter == Delimiter::kWhitespace) {
    for (;;) {
      while (p != end && is_blank(*p)) ++p;
      if (p == end) return index;
      const char* b = p;
      while (p != end && !is_blank(*p)) ++p;
      on_field(index++, b, p);
    }
  }
  const char sep = delimiter_char(delimiter);
  for (;;) {
    const char* b;
    const char* e;
    const char* d = delimited_field(p, end, sep, b, e);
    on_field(index++, b, e);
    if (d == nullptr) return index;
    p = d + 1;
  }
}

std::vector<std::string_view> split_fields(std::string_view line, Delimiter delimiter) {
  std::vector<std::string_view> out;
  for_each_field(line, delimiter, [&](std::size_t, const char* b, const char* e) {
    out.emplace_back(b, static_cast<std::size_t>(e - b));
  });
  return out;
}

Delimiter detect_delimiter(const std::vector<std::string_view>& lines) {
  // Prefer a separator present with the same count on every line, then one merely present
  // on every line (the row-count check reports the odd line); else blanks separate.
  for (const bool need_same_count : {true, false}) {
    for (const Delimiter d : {Delimiter::kTab, Delimiter::kSemicolon, Delimiter::kComma}) {
      const char c = delimiter_char(d);
      bool ok = !lines.empty();
      std::ptrdiff_t first_count = -1;
      for (std::string_view line : lines) {
        const auto count = std::count(line.begin(), line.end(), c);
        if (count == 0 || (need_same_count && first_count >= 0 && count != first_count)) {
          ok = false;
          break;
        }
        first_count = count;
      }
      if (ok) return d;
    }
  }
  return Delimiter::kWhitespace;
}

/// True when FIELD reads as a number; with DECIMAL_COMMA, a comma in it reads as the point.
bool is_number_in(std::string_view field, bool decimal_comma) {
  if (!decimal_comma || field.find(',') == std::string_view::npos) return is_number(field);
  std::string copy(field);
  std::replace(copy.begin(), copy.end(), ',', '.');
  return is_number(copy);
}

/// A decimal comma: the separator is not a comma, some field of the data lines (all but the
/// first, which may be the header) holds a comma, and every such field is a number with a point
/// in its place.
bool detect_decimal_comma(const std::vector<std::string_view>& lines, Delimiter delimiter) {
  if (delimiter == Delimiter::kComma) return false;
  bool some = false;
  for (std::size_t l = 1; l < lines.size(); ++l) {
    for (std::string_view f : split_fields(lines[l], delimiter)) {
      if (f.find(',') == std::string_view::npos) continue;
      if (!is_number_in(f, true)) return false;
      some = true;
    }
  }
  if (lines.size() == 1) {  // one line: it is data when its comma fields are numbers
    for (std::string_view f : split_fields(lines[0], delimiter)) {
      if (f.find(',') == std::string_view::npos) continue;
      if (!is_number_in(f, true)) return false;
      some = true;
    }
  }
  return some;
}

std::string header_name(std::string_view field) {
  const char* b = field.data();
  const char* e = b + field.size();
  unquote(b, e);
  return std::string(b, e);
}

}  // namespace

SniffedTable sniff_layout(LineSource& source, const std::string& path, Delimiter requested) {
  SniffedTable table;
  TableLayout& layout = table.layout;
  layout.path = path;
  std::string_view head = source.peek(kSniffBytes);
  if (head.empty()) fail(path, 0, 0, "file is empty");
  if (head.substr(0, 2) == "\xFF\xFE" || head.substr(0, 2) == "\xFE\xFF") {
    fail(path, 1, 1, "text is UTF-16 encoded; save it as UTF-8 or ASCII");
  }
  if (const auto nul = head.find('\0'); nul != std::string_view::npos) {
    const std::string_view before = head.substr(0, nul);
    const auto line = 1 + std::count(before.begin(), before.end(), '\n');
    const auto line_start = before.rfind('\n');
    const auto column = line_start == std::string_view::npos ? nul + 1 : nul - line_start;
    fail(path, line, static_cast<std::int64_t>(column), "binary data (NUL byte): not a text table");
  }

  // The first content lines, with their line numbers (views into the peeked buffer).
  std::vector<std::string_view> lines;
  std::vector<std::int64_t> numbers;
  std::string_view comment;  // the last '#' line before the first content line
  std::int64_t comment_line = 0;
  for (std::size_t want = kSniffBytes;; want *= 2) {
    head = source.peek(want);
    lines.clear();
    numbers.clear();
    comment = {};
    comment_line = 0;
    std::int64_t number = 0;
    std::size_t pos = 0;
    std::size_t bytes = 0;
    while (pos < head.size() && lines.size() < kSniffLines) {
      const auto nl = head.find('\n', pos);
      if (nl == std::string_view::npos && !source.at_eof()) break;  // incomplete line
      const auto stop = nl == std::string_view::npos ? head.size() : nl;
      std::string_view line = head.substr(pos, stop - pos);
      bytes += line.size() + 1;
      pos = stop + 1;
      ++number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (number == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
        line.remove_prefix(kUtf8Bom.size());
      }
      if (is_content(line)) {
        lines.push_back(line);
        numbers.push_back(number);
      } else if (lines.empty() && line.find('#') != std::string_view::npos) {
        comment = line;
        comment_line = number;
      }
    }
    table.mean_line_bytes =
        number > 0 ? static_cast<double>(bytes) / static_cast<double>(number) : 0;
    if (lines.size() >= 2 || source.at_eof() || want >= kMaxSniffBytes) break;
  }
  if (lines.empty()) {
    if (source.at_eof()) fail(path, 0, 0, "no data rows (only comments and blank lines)");
    fail(path, 0, 0, "no data row in the first 8 MiB: not a numeric text table");
  }

  layout.delimiter = requested != Delimiter::kAuto ? requested : detect_delimiter(lines);
  layout.decimal_comma = detect_decimal_comma(lines, layout.delimiter);
  const auto number = [&layout](std::string_view f) {
    return is_number_in(f, layout.decimal_comma);
  };
  const std::vector<std::string_view> first = split_fields(lines[0], layout.delimiter);
  // A header row holds no number at all; a row mixing words and numbers is a data row with
  // a malformed token, which the read loop then reports precisely.
  const bool header = std::none_of(first.begin(), first.end(), number);
  layout.column_count = first.size();
  if (!header && comment_line > 0) {
    // A header written as a comment (EuRoC, TUM-VI: "#timestamp [ns],w_RS_S_x [rad s^-1],…").
    std::string_view names = comment.substr(comment.find('#'));
    while (!names.empty() && (names.front() == '#' || is_blank(names.front()))) {
      names.remove_prefix(1);
    }
    const std::vector<std::string_view> fields = split_fields(names, layout.delimiter);
    const bool all_names = std::none_of(fields.begin(), fields.end(),
                                        [&](std::string_view f) { return f.empty() || number(f); });
    if (fields.size() >= 2 && fields.size() == first.size() && all_names) {
      layout.header_line = comment_line;
      for (std::string_view f : fields) layout.column_names.push_back(header_name(f));
    }
  }
  if (header) {
    layout.header_line = numbers[0];
    for (std::string_view f : first) layout.column_names.push_back(header_name(f));
    if (lines.size() >= 2) {
      table.first_data_line = numbers[1];
    } else if (source.at_eof()) {
      fail(path, numbers[0], 0, "header row but no data rows");
    }
  } else {
    table.first_data_line = numbers[0];
  }
  return table;
}

}  // namespace csv_detail

// ---------------------------------------------------------------------------------------------

std::string TableLayout::column_label(std::size_t index) const {
  const std::string number = "column " + std::to_string(index + 1);
  if (index < column_names.size() && !column_names[index].empty()) {
    // Built with append(): GCC 12 raises a false -Wrestrict on `"'" + show(…)` here.
    std::string label = "'";
    label.append(csv_detail::show(column_names[index])).append("' (").append(number).append(")");
    return label;
  }
  return number;
}

std::string TableLayout::describe_columns() const {
  if (!has_header()) {
    return column_count == 1
               ? std::string("1 (no header row)")
               : "1.." + std::to_string(column_count) + " (no header row; use 1-based indices)";
  }
  constexpr std::size_t kMaxListed = 40;  // keep error messages one readable line
  std::string out;
  for (std::size_t i = 0; i < column_names.size(); ++i) {
    if (i == kMaxListed) {
      out += ", ... (" + std::to_string(column_names.size() - kMaxListed) + " more)";
      break;
    }
    if (i > 0) out += ", ";
    out += column_names[i].empty() ? "(unnamed " + std::to_string(i + 1) + ")"
                                   : csv_detail::show(column_names[i]);
  }
  return out;
}

}  // namespace imunoise::io
