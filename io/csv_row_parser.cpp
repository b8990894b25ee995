/// @file
/// @brief A line to a row, and the messages of refused lines (see csv_row_parser.h).
#include "io/csv_row_parser.h"

#include <cmath>
#include <cstring>

#include "io/decimal_number.h"

namespace imunoise::io::csv_detail {

namespace {

/// parse_double of [B, E) with its comma (at most one) read as the decimal point. Kept out of
/// line: only decimal-comma tables take it.
[[gnu::noinline]] bool parse_with_decimal_comma(const char* b, const char* e, double& out) {
  const char* comma =
      static_cast<const char*>(std::memchr(b, ',', static_cast<std::size_t>(e - b)));
  if (comma == nullptr) return parse_double(b, e, out);
  constexpr std::ptrdiff_t kMax = 64;  // longer is no number a table holds
  if (e - b > kMax) return false;
  char copy[kMax];
  std::memcpy(copy, b, static_cast<std::size_t>(e - b));
  copy[comma - b] = '.';
  const char* c = copy;
  return std::memchr(comma + 1, ',', static_cast<std::size_t>(e - comma - 1)) == nullptr &&
         parse_double(c, c + (e - b), out);
}

/// Converts field J = [b, e) (trimmed) of the line starting at LINE_BEGIN. False with ERROR
/// set when the field is refused.
inline bool convert_field(const ReadPlan& plan, std::size_t j, const char* line_begin,
                          const char* b, const char* e, RowValues& row, RowError& error) {
  const int slot = plan.slot_of[j];
  if (slot < 0) return true;  // not requested: counted, not converted
  const auto s = static_cast<std::size_t>(slot);
  const auto column = static_cast<std::int64_t>(b - line_begin) + 1;
  if (b == e) {
    error = {RowProblem::kEmptyField, 0, column, j, 0, {}};
    return false;
  }
  row.is_integer[s] = plan.relative[s] && parse_int64(b, e, row.integer[s]);
  if (row.is_integer[s]) return true;
  double v = 0.0;
  if (plan.decimal_comma && !parse_with_decimal_comma(b, e, v)) {
    error = {RowProblem::kMalformedNumber, 0, column, j, 0, {b, static_cast<std::size_t>(e - b)}};
    return false;
  }
  if (!plan.decimal_comma && !parse_double(b, e, v)) {
    error = {RowProblem::kMalformedNumber, 0, column, j, 0, {b, static_cast<std::size_t>(e - b)}};
    return false;
  }
  if (!std::isfinite(v)) {
    if (!plan.drop_non_finite) {
      error = {RowProblem::kNonFinite, 0, column, j, 0, {b, static_cast<std::size_t>(e - b)}};
      return false;
    }
    ++row.non_finite;
  }
  row.value[s] = v;
  return true;
}

/// The fast path of a requested plain column: a decimal number that ends where the field
/// ends. Then the field is exactly the number's bytes (no blanks, quotes or '+'), and
/// parse_double on it would take the same parse_decimal_prefix path: same value. P moves past
/// the number.
inline bool convert_plain_number(const ReadPlan& plan, std::size_t j, const char*& p,
                                 const char* end, RowValues& row) {
  if (j >= plan.column_count) return false;
  const int slot = plan.slot_of[j];
  if (slot < 0 || plan.relative[static_cast<std::size_t>(slot)]) return false;
  const char* q = p;
  double v = 0.0;
  if (!parse_decimal_prefix(q, end, v)) return false;
  if (q != end) {
    const bool field_ends =
        plan.delimiter == Delimiter::kWhitespace ? is_blank(*q) : *q == plan.separator;
    if (!field_ends) return false;
  }
  row.value[static_cast<std::size_t>(slot)] = v;
  p = q;
  return true;
}

}  // namespace

/// Splits a content line like for_each_field and converts the requested fields, in field
/// order, so the first refused field is the one reported. False with ERROR (line unset) when
/// the line is refused; ROW.non_finite > 0 means the row is to be dropped.
bool parse_row(const ReadPlan& plan, std::string_view line, RowValues& row, RowError& error) {
  row.non_finite = 0;
  const char* const begin = line.data();
  const char* const end = begin + line.size();
  const std::size_t ncols = plan.column_count;
  const char* p = begin;
  std::size_t count = 0;
  const char* extra_field = nullptr;  // first field beyond the expected count
  if (plan.delimiter == Delimiter::kWhitespace) {
    for (;;) {
      while (p != end && is_blank(*p)) ++p;
      if (p == end) break;
      if (convert_plain_number(plan, count, p, end, row)) {
        ++count;
        continue;
      }
      const char* b = p;
      while (p != end && !is_blank(*p)) ++p;
      if (count < ncols) {
        if (!convert_field(plan, count, begin, b, p, row, error)) return false;
      } else if (count == ncols) {
        extra_field = b;
      }
      ++count;
    }
  } else {
    const char sep = plan.separator;
    for (;;) {
      if (convert_plain_number(plan, count, p, end, row)) {
        ++count;
        if (p == end) break;
        ++p;  // past the separator
        continue;
      }
      const char* b;
      const char* e;
      const char* d = delimited_field(p, end, sep, b, e);
      if (count < ncols) {
        if (!convert_field(plan, count, begin, b, e, row, error)) return false;
      } else if (count == ncols) {
        extra_field = b;
      }
      ++count;
      if (d == nullptr) break;
      p = d + 1;
    }
  }
  if (count != ncols) {
    const auto column = extra_field != nullptr ? static_cast<std::int64_t>(extra_field - begin) + 1
                                               : static_cast<std::int64_t>(line.size()) + 1;
    error = {RowProblem::kColumnCount, 0, column, 0, count, {}};
    return false;
  }
  return true;
}

std::string describe(const RowError& error, const TableLayout& layout,
                     const std::string& count_origin) {
  switch (error.problem) {
    case RowProblem::kEmptyField:
      return "empty field in " + layout.column_label(error.field);
    case RowProblem::kMalformedNumber:
      return "malformed number '" + show(error.token) + "' in " + layout.column_label(error.field);
    case RowProblem::kNonFinite:
      return "non-finite value '" + show(error.token) + "' in " + layout.column_label(error.field) +
             " (set drop_non_finite / --drop-non-finite to drop such rows)";
    case RowProblem::kColumnCount:
      return "expected " + std::to_string(layout.column_count) + " columns (" + count_origin +
             "), found " + std::to_string(error.fields_found);
    case RowProblem::kLineTooLong:
      return "line longer than 16 MiB: not a numeric text table";
    case RowProblem::kNone:
      break;
  }
  return "internal error: no row problem";
}

}  // namespace imunoise::io::csv_detail
