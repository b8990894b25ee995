/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): finding a table's layout from its first
/// lines (TableLayout, declared in io/csv_reader.h, is defined here too). Skips '#' comment and
/// blank lines, CRLF and a UTF-8 BOM; finds the delimiter (or takes the one requested); takes
/// the first content line as a header when it holds no number, else addresses the columns by
/// position. Refuses empty, UTF-16, binary and comment-only files.
#pragma once

#include <cstdint>
#include <string>

#include "io/csv_reader.h"
#include "io/input_config.h"

namespace imunoise::io::csv_detail {

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

}  // namespace imunoise::io::csv_detail
