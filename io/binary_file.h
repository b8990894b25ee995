/// @file
/// @brief Bounded reading of binary log files (internal to the readers of ROS bags, MCAP and
/// ULog files): a file read by offset whose every length is checked against the file size
/// before anything is allocated, and a little-endian cursor over bytes in memory whose every
/// read is checked against what is left. Both report a problem as the InputError
/// "FILE: byte offset N: problem", N counted from the start of the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace imunoise::io {

/// InputError "PATH: byte offset OFFSET: PROBLEM".
[[noreturn]] void throw_at_offset(const std::string& path, std::uint64_t offset,
                                  const std::string& problem);

/// A regular file opened for reading by offset (pread). Not copyable.
class BinaryFile {
 public:
  /// Opens PATH; InputError when it does not exist, is not a regular file or cannot be read.
  explicit BinaryFile(std::string path);
  ~BinaryFile();
  BinaryFile(const BinaryFile&) = delete;
  BinaryFile& operator=(const BinaryFile&) = delete;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }

  /// The COUNT bytes at OFFSET into OUT (resized to COUNT). WHAT names the bytes in the error
  /// when they lie beyond the end of the file ("truncated WHAT: it needs COUNT bytes at
  /// OFFSET, the file has N"); checked before OUT is resized.
  void read(std::uint64_t offset, std::uint64_t count, std::vector<std::uint8_t>& out,
            std::string_view what) const;

  /// As read(), but at most COUNT bytes: fewer at the end of the file. Returns how many.
  std::size_t read_some(std::uint64_t offset, std::uint64_t count,
                        std::vector<std::uint8_t>& out) const;

  /// A view of the COUNT bytes at OFFSET, through a read-ahead buffer of at least 1 MiB (so
  /// that many small records cost few reads); valid until the next call. Checked as read().
  std::span<const std::uint8_t> view(std::uint64_t offset, std::uint64_t count,
                                     std::string_view what);

  /// throw_at_offset for this file.
  [[noreturn]] void fail(std::uint64_t offset, const std::string& problem) const {
    throw_at_offset(path_, offset, problem);
  }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::vector<std::uint8_t> window_;  // the bytes of view(), from window_offset_
  std::uint64_t window_offset_ = 0;
};

/// Little-endian reads over bytes in memory that begin at file offset BASE (the offset the
/// errors name; for a decompressed chunk, the chunk's offset in the file, and the message then
/// says "in the chunk at …"). Every read checks what is left and throws InputError when the
/// bytes run out.
class ByteCursor {
 public:
  /// CONTEXT, when not empty, is added to every message ("in the chunk at offset 4117").
  ByteCursor(std::span<const std::uint8_t> bytes, const std::string& path, std::uint64_t base,
             std::string context = {})
      : bytes_(bytes), path_(&path), base_(base), context_(std::move(context)) {}

  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool at_end() const { return pos_ == bytes_.size(); }
  /// The file offset of the next byte (or, within a decompressed chunk, the chunk's offset).
  std::uint64_t offset() const { return context_.empty() ? base_ + pos_ : base_; }

  std::uint8_t u8(std::string_view what);
  std::uint16_t u16(std::string_view what);
  std::uint32_t u32(std::string_view what);
  std::uint64_t u64(std::string_view what);
  /// The next COUNT bytes, as a view.
  std::span<const std::uint8_t> bytes(std::uint64_t count, std::string_view what);
  /// A string of a 32-bit length then that many bytes (MCAP, ROS connection fields).
  std::string_view string32(std::string_view what);
  void skip(std::uint64_t count, std::string_view what) { (void)bytes(count, what); }

  /// InputError at the cursor: "PATH: byte offset N: PROBLEM[ CONTEXT]".
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void need(std::uint64_t count, std::string_view what) const;

  std::span<const std::uint8_t> bytes_;
  const std::string* path_;
  std::uint64_t base_;
  std::string context_;
  std::size_t pos_ = 0;
};

/// Little-endian loads from at least 2, 4, 8 bytes at P.
inline std::uint16_t load_le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
inline std::uint32_t load_le32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
         (std::uint32_t{p[3]} << 24);
}
inline std::uint64_t load_le64(const std::uint8_t* p) {
  return std::uint64_t{load_le32(p)} | (std::uint64_t{load_le32(p + 4)} << 32);
}

/// TEXT fit for a message: printable ASCII kept (at most 80 characters, then "..."), other
/// bytes (and the quote and backslash) as \xNN.
std::string printable_bytes(std::string_view text);
/// printable_bytes(TEXT) in single quotes.
std::string quoted_bytes(std::string_view text);

}  // namespace imunoise::io
