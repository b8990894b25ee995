/// @file
/// @brief What reading a numeric text table gives (io/csv_reader.h's TableReader): the
/// requested columns, the rows dropped and the map of rows to file lines; and how the read is
/// divided between threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace imunoise::io {

/// Maps 0-based data-row indices to 1-based file lines without storing one entry per row:
/// only rows after skipped lines (comments, blanks, dropped rows) get an entry.
class LineMap {
 public:
  void add(std::int64_t row, std::int64_t line);  ///< call for rows in increasing order
  /// Same as add(row + i, line + i) for i in [0, count).
  void add_run(std::int64_t row, std::int64_t line, std::int64_t count);
  std::int64_t line_of(std::size_t row) const;  ///< 0 if no row was added

  friend bool operator==(const LineMap&, const LineMap&) = default;

 private:
  std::vector<std::pair<std::int64_t, std::int64_t>> breaks_;  // (row, line), line − row changes
  std::int64_t next_row_ = 0;
  std::int64_t next_line_ = 0;
};

/// One column to extract.
struct ColumnRequest {
  std::size_t index = 0;  ///< 0-based column index
  /// Store value − first value (exact for integer tokens, e.g. ns stamps beyond 2^53).
  bool relative_to_first = false;
};

/// Extracted columns, in request order.
struct TableData {
  std::vector<std::vector<double>> columns;
  std::vector<double> first_values;     ///< first kept value of each column, as written
  std::int64_t non_finite_dropped = 0;  ///< NaN/Inf values in dropped rows
  std::int64_t rows_dropped = 0;        ///< rows dropped for NaN/Inf
  std::int64_t first_data_line = 0;     ///< line of the first kept row
  LineMap lines;                        ///< row → file line
};

/// How TableReader::read divides its work. The defaults suit every caller; the chunk and size
/// knobs exist so tests can force the parallel path on small files.
struct ReadParallelism {
  unsigned threads = 0;  ///< worker threads including the caller; 0 = hardware concurrency
  /// Regular files at least this large are memory-mapped and parsed by chunks; smaller ones
  /// (and pipes) are streamed, where starting threads does not pay.
  std::size_t min_mapped_bytes = std::size_t{4} << 20;
  std::size_t chunk_bytes = 0;  ///< bytes per chunk (rounded up to a line end); 0 = automatic
};

}  // namespace imunoise::io
