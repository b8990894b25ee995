/// @file
/// @brief TableReader (see csv_reader.h): opens and sniffs a table (io/table_layout), plans
/// a read (which file column goes to which output slot), streams small files and pipes
/// through io/line_source or hands large regular files to io/csv_chunked_parse, and
/// assembles the TableData; LineMap.
#include "io/csv_reader.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <system_error>

#include "common/errors.h"
#include "common/huge_pages.h"
#include "common/parallel_for.h"
#include "io/csv_chunked_parse.h"
#include "io/csv_row_parser.h"
#include "io/csv_text.h"
#include "io/line_source.h"
#include "io/table_layout.h"

namespace imunoise::io {

using namespace csv_detail;  // the parts of the reader (io/*.h, namespace csv_detail)

struct TableReader::Impl {
  std::string path;
  LineSource source;
  TableLayout layout;
  std::int64_t first_data_line = 0;  // first content line that is not the header
  double mean_line_bytes = 0.0;
  bool consumed = false;

  explicit Impl(std::string p) : path(std::move(p)), source(path) {}

  [[noreturn]] void fail(std::int64_t line, std::int64_t column, const std::string& what) const {
    throw InputError(located_message(path, line, column, what));
  }

  /// The streamed path: every line through ROWS, in 1 MiB blocks. Returns the kept rows.
  std::int64_t read_streamed(SequentialRows& rows, const ProgressCallback& progress,
                             std::vector<std::vector<double>>& values) {
    // Only while this call runs: the callback is the caller's.
    struct ProgressScope {
      LineSource& source;
      ~ProgressScope() { source.set_progress(nullptr); }
    } progress_scope{source};
    if (progress) source.set_progress(&progress);
    if (source.size_hint() > 0 && mean_line_bytes > 0.0) {
      const double estimate = static_cast<double>(source.size_hint()) / mean_line_bytes;
      const auto count = static_cast<std::size_t>(
          std::min(estimate * 1.02 + 16.0, static_cast<double>(source.size_hint() / 2 + 16)));
      for (auto& v : values) reserve_huge_pages(v, count);
    }
    // Sizes and pointers hoisted: VALUES is passed to read_mapped (another unit) too, so the
    // compiler cannot see that push_back leaves it alone, and would reload them per value.
    const std::size_t slots = values.size();
    std::vector<double>* const columns = values.data();
    const double* const row = rows.values().data();
    std::string_view line;
    while (source.next(line)) {
      if (!rows.take(line, source.line_number())) continue;
      for (std::size_t s = 0; s < slots; ++s) columns[s].push_back(row[s]);
    }
    return rows.kept();
  }
};

TableReader::TableReader(std::string path, Delimiter delimiter)
    : impl_(std::make_unique<Impl>(std::move(path))) {
  SniffedTable sniffed = sniff_layout(impl_->source, impl_->path, delimiter);
  impl_->layout = std::move(sniffed.layout);
  impl_->first_data_line = sniffed.first_data_line;
  impl_->mean_line_bytes = sniffed.mean_line_bytes;
}

TableReader::~TableReader() = default;

const TableLayout& TableReader::layout() const { return impl_->layout; }

std::optional<std::size_t> TableReader::find_column(std::string_view selector) const {
  const TableLayout& layout = impl_->layout;
  for (std::size_t i = 0; i < layout.column_names.size(); ++i) {
    if (layout.column_names[i] == selector) return i;
  }
  std::size_t index = 0;
  const auto [p, ec] = std::from_chars(selector.data(), selector.data() + selector.size(), index);
  if (ec == std::errc() && p == selector.data() + selector.size() && index >= 1 &&
      index <= layout.column_count) {
    return index - 1;
  }
  return std::nullopt;
}

std::size_t TableReader::resolve_column(std::string_view selector) const {
  if (const auto found = find_column(selector)) return *found;
  const TableLayout& layout = impl_->layout;
  const bool numeric =
      !selector.empty() &&
      std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; });
  std::string what;
  if (numeric) {
    what = "column index " + show(selector) + " out of range: the file has " +
           std::to_string(layout.column_count) + " column(s), indices start at 1";
  } else {
    what = "unknown column '" + show(selector) + "'";
  }
  what += " (available columns: " + layout.describe_columns() + ")";
  impl_->fail(layout.header_line, 0, what);
}

TableData TableReader::read(std::span<const ColumnRequest> columns, bool drop_non_finite,
                            const ProgressCallback& progress, const ReadParallelism& parallelism) {
  Impl& im = *impl_;
  IMUNOISE_EXPECT(!im.consumed, "TableReader::read called twice");
  im.consumed = true;
  const TableLayout& layout = im.layout;

  // slot_of[column] = output slot or -1; a column requested twice is parsed once.
  ReadPlan plan;
  plan.column_count = layout.column_count;
  plan.delimiter = layout.delimiter;
  plan.separator = delimiter_char(layout.delimiter);
  plan.drop_non_finite = drop_non_finite;
  plan.decimal_comma = layout.decimal_comma;
  plan.slot_of.assign(plan.column_count, -1);
  std::vector<std::size_t> output_slot(columns.size());
  for (std::size_t r = 0; r < columns.size(); ++r) {
    const ColumnRequest& req = columns[r];
    IMUNOISE_EXPECT(req.index < plan.column_count, "TableReader::read: column index");
    int& slot = plan.slot_of[req.index];
    if (slot < 0) {
      slot = static_cast<int>(plan.relative.size());
      plan.relative.push_back(req.relative_to_first);
    } else if (static_cast<bool>(plan.relative[static_cast<std::size_t>(slot)]) !=
               req.relative_to_first) {
      throw ContractViolation("TableReader::read: column requested both relative and not");
    }
    output_slot[r] = static_cast<std::size_t>(slot);
  }
  const std::size_t nslots = plan.slot_count();

  TableData data;
  std::vector<std::vector<double>> values(nslots);
  Origin origin(nslots);
  const std::string count_origin =
      layout.has_header()
          ? "as in the header on line " + std::to_string(layout.header_line)
          : "as in the first data row on line " + std::to_string(im.first_data_line);
  SequentialRows rows(plan, layout, layout.header_line, count_origin, data, origin);

  MappedText mapped;
  const bool use_mapping = im.source.size_hint() > 0 &&
                           im.source.size_hint() >= parallelism.min_mapped_bytes &&
                           mapped.map(im.source.fd());
  std::int64_t kept = 0;
  if (use_mapping) {
    const unsigned threads = resolve_threads(parallelism.threads);
    // Whatever was parsed from a file that shrank meanwhile is not its content: that is the
    // error, even when the zeros read past its end made a row fail first.
    const auto shrank = [&] {
      im.fail(0, 0,
              "the file shrank while it was read (it had " + std::to_string(mapped.size()) +
                  " bytes when opened); read it again once nothing writes to it");
    };
    try {
      kept = read_mapped(mapped, plan, rows, origin, threads, parallelism.chunk_bytes, progress,
                         values, data);
    } catch (...) {
      if (mapped.truncated()) shrank();
      throw;
    }
    if (mapped.truncated()) shrank();
  } else {
    kept = im.read_streamed(rows, progress, values);
  }

  if (kept == 0) {
    if (data.rows_dropped > 0) {
      im.fail(0, 0,
              "no data rows left after dropping " + std::to_string(data.rows_dropped) +
                  " row(s) holding NaN/Inf");
    }
    im.fail(layout.header_line, 0, "header row but no data rows");
  }

  data.columns.resize(columns.size());
  data.first_values.resize(columns.size());
  for (std::size_t r = 0; r < columns.size(); ++r) {
    const std::size_t s = output_slot[r];
    // Move each slot's vector to its last request; earlier duplicates get copies.
    bool last_use = true;
    for (std::size_t later = r + 1; later < columns.size(); ++later) {
      last_use = last_use && output_slot[later] != s;
    }
    data.columns[r] = last_use ? std::move(values[s]) : values[s];
    data.first_values[r] = plan.relative[s] ? origin.value[s] : data.columns[r].front();
  }
  return data;
}

}  // namespace imunoise::io
