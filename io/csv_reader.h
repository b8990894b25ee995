/// @file
/// @brief Reader of numeric text tables (CSV, TSV, space- or semicolon-separated, one number
/// per line), and the two entry points built on it: `read_series` (one column, for
/// `imunoise allan`) and `read_recording` (an IMU recording in SI). Large regular files are
/// memory-mapped and parsed by chunks in parallel; pipes and small files are streamed. Both
/// paths give the same values, line numbers and errors.
///
/// Accepted: an optional header row of column names (else columns are addressed by 1-based
/// index), '#' comment lines and blank lines anywhere, CRLF, a UTF-8 BOM, no final newline.
/// Every error is an InputError "FILE:LINE:COL: problem" showing the offending token.
///
/// The parts, internal to io/ (namespace csv_detail): io/decimal_number.h (a token to a
/// number), io/csv_text.h (shared text conventions), io/table_layout (sniffing the layout),
/// io/line_source (the streaming source), io/csv_row_parser (a line to a row),
/// io/csv_chunked_parse (the mapped parallel parse); io/csv_reader.cpp is TableReader,
/// io/imu_column_mapping.cpp read_series and read_recording.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/progress_callback.h"
#include "io/input_config.h"
#include "io/table_data.h"
#include "io/table_layout.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// Opens a table and finds its layout; read() then parses the rows: memory-mapped by chunks on
/// several threads, or streamed in 1 MiB blocks (std::from_chars, no per-line allocation).
/// Only requested columns are converted, but every row's column count is checked.
class TableReader {
 public:
  /// Throws InputError when the file cannot be opened, is empty, or has no data rows.
  explicit TableReader(std::string path, Delimiter delimiter = Delimiter::kAuto);
  ~TableReader();
  TableReader(const TableReader&) = delete;
  TableReader& operator=(const TableReader&) = delete;

  const TableLayout& layout() const;

  /// Column addressed by header name, else by 1-based index; nullopt if neither.
  std::optional<std::size_t> find_column(std::string_view selector) const;
  /// As find_column; throws InputError listing the available columns.
  std::size_t resolve_column(std::string_view selector) const;

  /// Reads all rows once (a second call is a ContractViolation). NaN/Inf: InputError, or with
  /// drop_non_finite the row is dropped and counted. Throws InputError at the first malformed
  /// token or wrong column count. Every index must be below layout().column_count, and a
  /// column may be requested twice only with the same relative_to_first (else
  /// ContractViolation).
  /// PROGRESS (optional) gets ("reading", bytes parsed, file size) from the calling thread
  /// after each block or chunk of a regular file. The result and the error (the first in file
  /// order) do not depend on PARALLELISM.
  TableData read(std::span<const ColumnRequest> columns, bool drop_non_finite,
                 const ProgressCallback& progress = {}, const ReadParallelism& parallelism = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// @name Single series (`imunoise allan FILE [--column NAME|INDEX]`)
/// @{
struct SeriesReadOptions {
  std::string column;  ///< name, 1-based index, or empty = the only column
  bool drop_non_finite = false;
  Delimiter delimiter = Delimiter::kAuto;
  /// Also read the time column, if the header names one (time_s, time_ms, time_us, time_ns),
  /// converted to seconds relative to the first stamp.
  bool read_time = false;
  unsigned threads = 0;  ///< parsing threads (ReadParallelism::threads); 0 = hardware concurrency
};

struct Series {
  std::string source_path;
  std::string column_name;  ///< header name, or "column N" without a header
  std::vector<double> values;
  std::int64_t non_finite_dropped = 0;
  std::int64_t first_data_line = 0;
  std::string time_column;     ///< name of the time column read (empty: none)
  std::vector<double> time_s;  ///< its stamps [s] relative to the first (rows as `values`)
};

/// Reads one numeric column. With several columns and no `column`, the InputError lists them.
Series read_series(const std::string& path, const SeriesReadOptions& options);
/// @}

/// Reads an IMU recording per `config` (see InputConfig for the automatic mapping) and
/// converts it to SI: rates in rad/s and m/s², increments divided by the sample period.
/// Fills the sampling report; non-monotonic time stamps are reported, not fatal. PROGRESS
/// (optional) follows the bytes read, as in TableReader::read. THREADS parse large files
/// (ReadParallelism::threads; 0 = hardware concurrency); the result does not depend on it.
pipeline::Recording read_recording(const std::string& path, const InputConfig& config,
                                   const ProgressCallback& progress = {}, unsigned threads = 0);

}  // namespace imunoise::io
