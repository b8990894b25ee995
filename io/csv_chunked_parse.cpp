/// @file
/// @brief The mapped parallel parse of the CSV reader (see csv_chunked_parse.h).
#include "io/csv_chunked_parse.h"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstring>
#include <string_view>

#include "common/huge_pages.h"
#include "common/parallel_for.h"
#include "io/csv_text.h"

namespace imunoise::io::csv_detail {

MappedText::~MappedText() {
  guard_.reset();  // before the range can be reused by another mapping
  if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
}

bool MappedText::map(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return false;
  const auto size = static_cast<std::size_t>(st.st_size);
  void* at = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (at == MAP_FAILED) return false;
  data_ = static_cast<const char*>(at);
  size_ = size;
  guard_.emplace(at, size);
  ::madvise(at, size, MADV_SEQUENTIAL);  // a hint: more read-ahead on a cold cache
  return true;
}

void MappedText::release(const char* b, const char* e) const {
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto base = reinterpret_cast<std::uintptr_t>(data_);
  const std::uintptr_t from = (reinterpret_cast<std::uintptr_t>(b) + page - 1) / page * page;
  const std::uintptr_t to = std::max(from, reinterpret_cast<std::uintptr_t>(e) / page * page);
  if (to > from && from >= base) {
    ::madvise(reinterpret_cast<void*>(from), to - from, MADV_DONTNEED);
  }
}

namespace {

/// Cuts the next line off [p, end): strips "\n" and "\r\n". The caller strips the BOM.
inline std::string_view cut_line(const char*& p, const char* end) {
  const auto* nl =
      static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
  const char* line_end = nl != nullptr ? nl : end;
  std::string_view line(p, static_cast<std::size_t>(line_end - p));
  p = nl != nullptr ? nl + 1 : end;
  return line;
}

/// LineSource's limit, applied to a mapped line (CR included, as LineSource counts it).
inline bool line_too_long(std::string_view line) { return line.size() >= kMaxLineBytes; }

inline void strip_cr(std::string_view& line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
}

/// Consecutive kept rows on consecutive lines, chunk-local (LineMap::add_run after the join).
struct LineRun {
  std::int64_t row = 0;
  std::int64_t line = 0;
  std::int64_t count = 0;
};

/// A piece of the mapped data region, starting at a line start and ending after a newline (or
/// at the end of the file).
struct Chunk {
  const char* begin = nullptr;
  const char* end = nullptr;
  std::int64_t lines = 0;         // lines starting in the chunk (pass 1)
  std::int64_t lines_before = 0;  // file lines before the chunk
  std::size_t row_begin = 0;      // first output row it may fill
  std::size_t row_capacity = 0;   // rows it may fill: a bound on its kept rows
  std::size_t kept = 0;
  std::int64_t rows_dropped = 0;
  std::int64_t non_finite_dropped = 0;
  std::vector<LineRun> runs;
  RowError error;  // the chunk's first refused line (problem kNone: none)
};

/// Counts '\n' in [b, e), 8 bytes per step: a byte of x = word ^ "\n\n…" is zero exactly when
/// bit 7 of ((x & 0x7F…) + 0x7F…) | x is clear (no carry crosses a byte: each lane is ≤ 0xFE).
/// The multiply sums the 0/1 bytes into the top byte (at most 8: no carry out); a portable
/// popcount without -mpopcnt would be a library call.
std::int64_t count_newlines(const char* b, const char* e) {
  constexpr std::uint64_t kNewlines = 0x0A0A0A0A0A0A0A0Au;
  constexpr std::uint64_t kLow7 = 0x7F7F7F7F7F7F7F7Fu;
  std::int64_t n = 0;
  for (; e - b >= 8; b += 8) {
    std::uint64_t word;
    std::memcpy(&word, b, 8);
    const std::uint64_t x = word ^ kNewlines;
    const std::uint64_t found = ~(((x & kLow7) + kLow7) | x | kLow7) >> 7;  // 0 or 1 per byte
    n += static_cast<std::int64_t>((found * 0x0101010101010101u) >> 56);    // sum of the bytes
  }
  for (; b != e; ++b) n += *b == '\n';
  return n;
}

/// Parses CHUNK into its slice of the output columns (OUT[s] + chunk.row_begin …). Stops at
/// its first refused line, or early once a chunk before it (index < INDEX) has failed.
void parse_chunk(const ReadPlan& plan, const Origin& origin, Chunk& chunk, std::size_t index,
                 const std::vector<double*>& out, std::atomic<std::size_t>& first_failed) {
  constexpr std::int64_t kCheckEvery = 4096;  // lines between looks at first_failed
  RowValues row(plan.slot_count());
  const std::size_t slots = plan.slot_count();
  const char* p = chunk.begin;
  std::int64_t line_no = 0;  // within the chunk, 1-based
  std::size_t kept = 0;
  while (p != chunk.end) {
    std::string_view line = cut_line(p, chunk.end);
    ++line_no;
    if ((line_no % kCheckEvery) == 0 && first_failed.load(std::memory_order_relaxed) < index) {
      break;  // an earlier chunk's error wins; this chunk's rows no longer matter
    }
    if (line_too_long(line)) {
      chunk.error = {RowProblem::kLineTooLong, line_no, 0, 0, 0, {}};
      break;
    }
    strip_cr(line);  // line 1 (the only one with a BOM) is never in a chunk
    if (!is_content(line)) continue;
    if (!parse_row(plan, line, row, chunk.error)) {
      chunk.error.line = line_no;
      break;
    }
    if (row.non_finite > 0) {
      ++chunk.rows_dropped;
      chunk.non_finite_dropped += row.non_finite;
      continue;
    }
    assert(kept < chunk.row_capacity && "the bound on kept rows per chunk holds");
    const std::size_t at = chunk.row_begin + kept;
    for (std::size_t s = 0; s < slots; ++s) {
      out[s][at] = plan.relative[s] ? origin.relative(s, row) : row.value[s];
    }
    const auto row_index = static_cast<std::int64_t>(kept);
    if (chunk.runs.empty() || chunk.runs.back().row + chunk.runs.back().count != row_index ||
        chunk.runs.back().line + chunk.runs.back().count != line_no) {
      chunk.runs.push_back({row_index, line_no, 0});
    }
    ++chunk.runs.back().count;
    ++kept;
  }
  chunk.kept = kept;
  if (chunk.error.problem != RowProblem::kNone) {
    std::size_t seen = first_failed.load();
    while (index < seen && !first_failed.compare_exchange_weak(seen, index)) {
    }
  }
}

}  // namespace

std::int64_t read_mapped(const MappedText& text, const ReadPlan& plan, SequentialRows& rows,
                         const Origin& origin, unsigned threads, std::size_t chunk_bytes,
                         const ProgressCallback& progress, std::vector<std::vector<double>>& values,
                         TableData& data) {
  const char* p = text.begin();
  std::int64_t line_no = 0;
  std::vector<double> first_row;
  while (p != text.end()) {
    std::string_view line = cut_line(p, text.end());
    ++line_no;
    if (line_too_long(line)) {
      rows.fail({RowProblem::kLineTooLong, 0, 0, 0, 0, {}}, line_no);
    }
    strip_cr(line);
    if (line_no == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
      line.remove_prefix(kUtf8Bom.size());
    }
    if (rows.take(line, line_no)) {
      first_row = rows.values();
      break;
    }
  }
  if (rows.kept() == 0) return 0;

  // Chunks of the rest, each ending after a newline.
  const char* const region = p;
  const auto region_bytes = static_cast<std::size_t>(text.end() - region);
  if (chunk_bytes == 0) {
    constexpr std::size_t kMinChunk = std::size_t{1} << 20;
    constexpr std::size_t kMaxChunk = std::size_t{64} << 20;
    // Several chunks per thread: the load balances and progress moves.
    chunk_bytes = std::clamp(region_bytes / (std::size_t{8} * threads), kMinChunk, kMaxChunk);
  }
  std::vector<Chunk> chunks;
  for (const char* b = region; b != text.end();) {
    const char* e = text.end();
    if (static_cast<std::size_t>(text.end() - b) > chunk_bytes) {
      const char* cut = b + chunk_bytes;
      const auto* nl = static_cast<const char*>(
          std::memchr(cut - 1, '\n', static_cast<std::size_t>(text.end() - (cut - 1))));
      if (nl != nullptr) e = nl + 1;
    }
    chunks.push_back(Chunk{});
    chunks.back().begin = b;
    chunks.back().end = e;
    b = e;
  }

  // Pass 1: lines per chunk (a final line without a newline counts too).
  const auto nothing = [] {};
  parallel_for(
      chunks.size(), threads,
      [&](std::size_t i) {
        Chunk& c = chunks[i];
        c.lines = count_newlines(c.begin, c.end) + (c.end[-1] != '\n' ? 1 : 0);
        text.release(c.begin, c.end);
      },
      nothing);
  // A kept row has all its fields, the requested ones not empty, and a line end (but the
  // last): a chunk of B bytes holds at most (B + 1) / (that + 1) of them. This caps the
  // output reserved for files of mostly blank or comment lines.
  const std::size_t min_row_bytes = plan.column_count - 1 + plan.slot_count();
  std::size_t bound = 1;  // row 0 is the first kept row
  std::int64_t lines_before = line_no;
  for (Chunk& c : chunks) {
    const auto bytes = static_cast<std::size_t>(c.end - c.begin);
    c.lines_before = lines_before;
    c.row_begin = bound;
    c.row_capacity = std::min(static_cast<std::size_t>(c.lines), (bytes + 1) / (min_row_bytes + 1));
    lines_before += c.lines;
    bound += c.row_capacity;
  }
  std::vector<double*> out(values.size());
  for (std::size_t s = 0; s < values.size(); ++s) {
    reserve_huge_pages(values[s], bound);
    values[s].resize(bound);
    values[s][0] = first_row[s];
    out[s] = values[s].data();
  }

  // Pass 2: parse. Progress counts the bytes of finished chunks, reported by this thread.
  const auto total = static_cast<std::int64_t>(text.size());
  std::atomic<std::int64_t> done{static_cast<std::int64_t>(region - text.begin())};
  std::atomic<std::size_t> first_failed{chunks.size()};
  parallel_for(
      chunks.size(), threads,
      [&](std::size_t i) {
        Chunk& c = chunks[i];
        if (first_failed.load() > i) {
          parse_chunk(plan, origin, c, i, out, first_failed);
          text.release(c.begin, c.end);
        }
        done.fetch_add(c.end - c.begin);
      },
      [&] { report_progress(progress, "reading", done.load(), total); });

  if (first_failed.load() < chunks.size()) {
    const Chunk& c = chunks[first_failed.load()];
    rows.fail(c.error, c.lines_before + c.error.line);
  }

  // Close the slices up in file order; in a file without skipped lines nothing moves.
  std::size_t kept = 1;
  for (const Chunk& c : chunks) {
    if (c.kept > 0 && c.row_begin != kept) {
      for (std::vector<double>& v : values) {
        std::memmove(v.data() + kept, v.data() + c.row_begin, c.kept * sizeof(double));
      }
    }
    for (const LineRun& run : c.runs) {
      data.lines.add_run(static_cast<std::int64_t>(kept) + run.row, c.lines_before + run.line,
                         run.count);
    }
    data.rows_dropped += c.rows_dropped;
    data.non_finite_dropped += c.non_finite_dropped;
    kept += c.kept;
  }
  for (std::vector<double>& v : values) v.resize(kept);
  report_progress(progress, "reading", total, total);
  return static_cast<std::int64_t>(kept);
}

}  // namespace imunoise::io::csv_detail
