/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): the memory-mapped, chunked, parallel
/// parse of a large regular file (TableReader::read maps files of at least
/// ReadParallelism::min_mapped_bytes, 4 MiB by default). The lines up to the first kept row
/// are taken in order (that row is the origin of relative columns); the rest is cut into
/// chunks at newlines, whose newline counts fix every line's number; the chunks are parsed in
/// parallel straight into the output, and the error reported is the earliest in the file. The
/// mapping is guarded (io/mapping_guard.h) against a file that shrinks meanwhile. Values,
/// line numbers and errors are those of the streamed path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/progress_callback.h"
#include "io/csv_row_parser.h"
#include "io/mapping_guard.h"
#include "io/table_data.h"
#include "io/table_layout.h"

namespace imunoise::io::csv_detail {

/// A read-only private mapping of a whole regular file, unmapped on destruction. Guarded
/// (io/mapping_guard.h): if the file shrinks while it is parsed, the pages past its new end
/// read as zeros instead of killing the process, and truncated() says so.
class MappedText {
 public:
  MappedText() = default;
  ~MappedText();
  MappedText(const MappedText&) = delete;
  MappedText& operator=(const MappedText&) = delete;

  /// Maps FD; false (nothing mapped) when the file is not a regular file or mmap fails.
  bool map(int fd);

  /// True when a page past the file's end was read: the file shrank after it was mapped.
  bool truncated() const { return guard_ && guard_->truncated(); }

  const char* begin() const { return data_; }
  const char* end() const { return data_ + size_; }
  std::size_t size() const { return size_; }

  /// Drops the mapping's pages wholly inside [b, e) from this process's memory (they stay in
  /// the page cache, and come back on the next access): the resident size then stays near the
  /// output's, not output + file.
  void release(const char* b, const char* e) const;

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  std::optional<MappingGuard> guard_;
};

/// The mapped path. Lines up to the first kept row go through ROWS in this thread (that row
/// is the origin of relative columns); the rest is cut into chunks at line ends. Pass 1
/// counts each chunk's lines, which bounds its rows and fixes where its slice of the output
/// starts; pass 2 parses the chunks in parallel straight into the output columns; then the
/// slices are closed up over skipped lines in file order. Returns the kept rows.
/// THREADS workers (including the caller) parse chunks of CHUNK_BYTES (0: automatic) into
/// VALUES (one vector per slot); DATA gets the line map and the drop counts. PROGRESS gets
/// ("reading", bytes, file size) from the calling thread. Throws the InputError of the
/// earliest refused line.
std::int64_t read_mapped(const MappedText& text, const ReadPlan& plan, SequentialRows& rows,
                         const Origin& origin, unsigned threads, std::size_t chunk_bytes,
                         const ProgressCallback& progress, std::vector<std::vector<double>>& values,
                         TableData& data);

}  // namespace imunoise::io::csv_detail
