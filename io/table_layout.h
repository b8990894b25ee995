/// @file
/// @brief The layout of a numeric text table (TableLayout) and, internal to the CSV reader
/// (io/csv_reader.h), finding it from the table's first lines. Skips '#' comment and
/// blank lines, CRLF and a UTF-8 BOM; finds the delimiter (or takes the one requested) and a
/// decimal comma; takes the first content line as a header when it holds no number, else the
/// last '#' comment line before it when that one, without its '#', splits into as many names
/// (two or more, none a number) as the first row has fields (EuRoC's `#timestamp [ns],…`), else
/// addresses the columns by position. Refuses empty, UTF-16, binary and comment-only files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/input_config.h"

namespace imunoise::io {

/// Shape of a table, found from its first lines.
struct TableLayout {
  std::string path;
  Delimiter delimiter = Delimiter::kWhitespace;  ///< resolved, never kAuto
  std::size_t column_count = 0;
  std::vector<std::string> column_names;  ///< header names; empty when there is no header
  std::int64_t header_line = 0;           ///< 1-based line of the header; 0 = none
  /// Numbers are written with a decimal comma ("1,5"): found when the separator is not a comma
  /// and the fields holding a comma read as numbers with a point in its place.
  bool decimal_comma = false;

  bool has_header() const { return !column_names.empty(); }
  /// "'gyro_x' (column 2)" with a header, "column 2" without (index is 0-based).
  std::string column_label(std::size_t index) const;
  /// "time_s, gyro_x, …" or "1..7 (no header row; use 1-based indices)".
  std::string describe_columns() const;
};

namespace csv_detail {

class LineSource;

/// What sniff_layout finds.
struct SniffedTable {
  TableLayout layout;
  std::int64_t first_data_line = 0;  ///< first content line that is not the header
  double mean_line_bytes = 0.0;      ///< mean bytes per line of the sniffed head (0: none)
};

/// Sniffs the table SOURCE reads (opened from PATH) by peeking at its first lines, which stay
/// unconsumed. REQUESTED = kAuto detects the delimiter. Throws InputError ("PATH:LINE:COL:
/// problem") when the file is empty, UTF-16, binary, or has no data row.
SniffedTable sniff_layout(LineSource& source, const std::string& path, Delimiter requested);

}  // namespace csv_detail
}  // namespace imunoise::io
