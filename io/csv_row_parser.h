/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): the conversion of one line into one
/// row, shared by the streamed and the memory-mapped paths so both give the same values and
/// the same errors. A ReadPlan says which columns go to which output slot; parse_row splits a
/// line, checks its column count and converts the requested fields; a refused line is a
/// RowError (data, so that workers neither allocate nor throw), made a message by describe()
/// once its line number is known; SequentialRows takes lines in file order and throws.
/// parse_row is one call per line, as it was before the reader was split; the per-field
/// helpers (the number parsing of io/decimal_number.h) are inlined into it in its own unit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "io/csv_text.h"
#include "io/input_config.h"
#include "io/table_data.h"
#include "io/table_layout.h"

namespace imunoise::io::csv_detail {

/// What one read() extracts, shared read-only by all workers.
struct ReadPlan {
  std::size_t column_count = 0;
  Delimiter delimiter = Delimiter::kWhitespace;
  char separator = ' ';
  bool drop_non_finite = false;
  bool decimal_comma = false;           // a ',' in a field is the decimal point
  std::vector<int> slot_of;             // per file column: output slot, or -1 when not read
  std::vector<unsigned char> relative;  // per slot; not vector<bool>: read per field
  std::size_t slot_count() const { return relative.size(); }
};

/// Why a line is refused.
enum class RowProblem {
  kNone,
  kEmptyField,
  kMalformedNumber,
  kNonFinite,
  kColumnCount,
  kLineTooLong,
};

/// A refused line, kept as data: workers then neither allocate nor throw, and the message is
/// written once the line's number in the file is known.
struct RowError {
  RowProblem problem = RowProblem::kNone;
  std::int64_t line = 0;         // 1-based; within its chunk until resolved
  std::int64_t column = 0;       // 1-based byte in the line; 0 = the whole line
  std::size_t field = 0;         // 0-based file column of a field problem
  std::size_t fields_found = 0;  // kColumnCount
  std::string_view token;        // the offending field (a view into the text)
};

/// The problem part of the message for ERROR ("malformed number 'x' in 'gyro_x' (column 2)").
/// COUNT_ORIGIN says where the expected column count comes from.
std::string describe(const RowError& error, const TableLayout& layout,
                     const std::string& count_origin);

/// One row's values per slot; scratch sized once per thread.
struct RowValues {
  explicit RowValues(std::size_t slots) : value(slots), integer(slots), is_integer(slots) {}
  std::vector<double> value;
  std::vector<std::int64_t> integer;  // relative slots holding an integer token
  std::vector<unsigned char> is_integer;
  std::int64_t non_finite = 0;  // NaN/Inf values (only when dropping)
};

/// The first kept row's relative columns: what every kept row is made relative to.
struct Origin {
  explicit Origin(std::size_t slots) : value(slots, 0.0), integer(slots, 0), is_integer(slots, 0) {}
  std::vector<double> value;  // as written (first_values)
  std::vector<std::int64_t> integer;
  std::vector<unsigned char> is_integer;

  void set(const ReadPlan& plan, const RowValues& row) {
    for (std::size_t s = 0; s < plan.slot_count(); ++s) {
      if (!plan.relative[s]) continue;
      is_integer[s] = row.is_integer[s];
      integer[s] = row.integer[s];
      value[s] = row.is_integer[s] ? static_cast<double>(row.integer[s]) : row.value[s];
    }
  }

  /// Slot S of ROW relative to the origin: exact integer subtraction when both are integers
  /// (ns stamps beyond 2^53), else in double.
  double relative(std::size_t s, const RowValues& row) const {
    std::int64_t diff = 0;
    if (row.is_integer[s] && is_integer[s] &&
        !__builtin_sub_overflow(row.integer[s], integer[s], &diff)) {
      return static_cast<double>(diff);
    }
    const double v = row.is_integer[s] ? static_cast<double>(row.integer[s]) : row.value[s];
    return v - value[s];
  }
};

/// Splits a content line as the sniffing does (for_each_field, io/table_layout.cpp) and
/// converts the requested fields, in field order, so the first refused field is the one
/// reported. False with ERROR (line unset) when the line is refused; ROW.non_finite > 0 means
/// the row is to be dropped.
bool parse_row(const ReadPlan& plan, std::string_view line, RowValues& row, RowError& error);

/// Sequential handling of lines in file order: the streamed path, and the mapped path up to
/// its first kept row. Throws at the first refused line.
class SequentialRows {
 public:
  SequentialRows(const ReadPlan& plan, const TableLayout& layout, std::int64_t header_line,
                 const std::string& count_origin, TableData& data, Origin& origin)
      : plan_(plan),
        layout_(layout),
        header_line_(header_line),
        count_origin_(count_origin),
        data_(data),
        origin_(origin),
        row_(plan.slot_count()) {}

  /// Takes line LINE_NO (CR and BOM stripped). True when it is kept, as row kept() − 1, with
  /// its final values (relative columns made relative) in values().
  bool take(std::string_view line, std::int64_t line_no) {
    if (!is_content(line) || line_no == header_line_) return false;
    RowError error;
    if (!parse_row(plan_, line, row_, error)) fail(error, line_no);
    if (row_.non_finite > 0) {
      ++data_.rows_dropped;
      data_.non_finite_dropped += row_.non_finite;
      return false;
    }
    if (kept_ == 0) {
      origin_.set(plan_, row_);
      data_.first_data_line = line_no;
    }
    for (std::size_t s = 0; s < plan_.slot_count(); ++s) {
      if (plan_.relative[s]) row_.value[s] = origin_.relative(s, row_);
    }
    data_.lines.add(kept_, line_no);
    ++kept_;
    return true;
  }

  /// The kept row's values per slot; the vector is sized once, so its data() stays valid.
  const std::vector<double>& values() const { return row_.value; }
  std::int64_t kept() const { return kept_; }

  /// Throws the InputError of ERROR on line LINE_NO of the file.
  [[noreturn]] void fail(const RowError& error, std::int64_t line_no) const {
    throw InputError(located_message(layout_.path, line_no, error.column,
                                     describe(error, layout_, count_origin_)));
  }

 private:
  const ReadPlan& plan_;
  const TableLayout& layout_;
  std::int64_t header_line_;
  const std::string& count_origin_;
  TableData& data_;
  Origin& origin_;
  RowValues row_;
  std::int64_t kept_ = 0;
};

}  // namespace imunoise::io::csv_detail
