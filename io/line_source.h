/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): the streaming source. Reads a file or
/// a pipe in 1 MiB blocks and hands out its lines as views into the buffer, without a
/// per-line allocation; the path small files and pipes take, and the sniffing of every table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "common/progress_callback.h"
#include "io/csv_text.h"

namespace imunoise::io::csv_detail {

/// Bytes asked of one read() call, and the buffer's starting size.
inline constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

/// Reads a file in large blocks and hands out lines as views into its buffer (valid until the
/// next call). Strips "\n", "\r\n" and a UTF-8 BOM on line 1; a last line without a newline is
/// still a line. Lines longer than kMaxLineBytes are an error, so memory stays bounded.
class LineSource {
 public:
  /// Opens PATH. Throws InputError when it cannot be opened or is a directory.
  explicit LineSource(const std::string& path);
  ~LineSource();
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  std::size_t size_hint() const { return size_hint_; }
  int fd() const { return fd_; }
  bool at_eof() const { return eof_; }
  /// Reports the bytes read after each block from now on (regular files only: the size is
  /// the total).
  void set_progress(const ProgressCallback* progress) { progress_ = progress; }

  /// The unconsumed bytes, after reading until at least `bytes` are buffered or EOF.
  std::string_view peek(std::size_t bytes) {
    while (end_ - pos_ < bytes && !eof_) read_more();
    return {buffer_.data() + pos_, end_ - pos_};
  }

  /// Next line, or false at end of file.
  bool next(std::string_view& line) {
    for (;;) {
      const char* base = buffer_.data();
      const void* nl = std::memchr(base + scan_, '\n', end_ - scan_);
      if (nl != nullptr) {
        const auto at = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
        line = {base + pos_, at - pos_};
        pos_ = scan_ = at + 1;
        break;
      }
      scan_ = end_;  // no newline in what we have: do not scan it again
      if (eof_) {
        if (pos_ == end_) return false;
        line = {base + pos_, end_ - pos_};
        pos_ = scan_ = end_;
        break;
      }
      read_more();
    }
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_number_ == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
      line.remove_prefix(kUtf8Bom.size());
    }
    return true;
  }

  std::int64_t line_number() const { return line_number_; }

 private:
  /// Reads the next block (keeping the unconsumed tail, growing the buffer up to the line
  /// limit), or sets EOF. Throws InputError on a read error or an overlong line.
  void read_more();

  std::string path_;
  int fd_ = -1;
  std::size_t size_hint_ = 0;
  std::vector<char> buffer_;
  std::size_t pos_ = 0;   // start of the unconsumed bytes
  std::size_t scan_ = 0;  // where the next newline search starts
  std::size_t end_ = 0;   // end of the valid bytes
  bool eof_ = false;
  std::int64_t line_number_ = 0;
  std::size_t bytes_read_ = 0;
  const ProgressCallback* progress_ = nullptr;  // not owned; set only during TableReader::read
};

}  // namespace imunoise::io::csv_detail
