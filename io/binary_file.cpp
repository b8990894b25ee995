/// @file
/// @brief Bounded reading of binary log files (see binary_file.h).
#include "io/binary_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/errors.h"

namespace imunoise::io {

void throw_at_offset(const std::string& path, std::uint64_t offset, const std::string& problem) {
  throw InputError(
      located_message(path, 0, 0, "byte offset " + std::to_string(offset) + ": " + problem));
}

BinaryFile::BinaryFile(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    throw InputError(
        located_message(path_, 0, 0, std::string("cannot open: ") + std::strerror(errno)));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(located_message(path_, 0, 0, "cannot open: not a regular file"));
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

BinaryFile::~BinaryFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t BinaryFile::read_some(std::uint64_t offset, std::uint64_t count,
                                  std::vector<std::uint8_t>& out) const {
  const std::uint64_t available = offset < size_ ? size_ - offset : 0;
  const std::uint64_t n = count < available ? count : available;
  out.resize(n);
  std::uint64_t done = 0;
  while (done < n) {
    const ssize_t got =
        ::pread(fd_, out.data() + done, n - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail(offset + done, std::string("read error: ") + std::strerror(errno));
    if (got == 0) {
      fail(offset + done, "the file ended early (was it changed while being read?)");
    }
    done += static_cast<std::uint64_t>(got);
  }
  return n;
}

void BinaryFile::read(std::uint64_t offset, std::uint64_t count, std::vector<std::uint8_t>& out,
                      std::string_view what) const {
  if (offset > size_ || count > size_ - offset) {
    fail(offset, "truncated " + std::string(what) + ": it needs " + std::to_string(count) +
                     " bytes here, the file has " +
                     std::to_string(offset < size_ ? size_ - offset : 0) + " (" +
                     std::to_string(size_) + " bytes in all)");
  }
  (void)read_some(offset, count, out);
}

std::span<const std::uint8_t> BinaryFile::view(std::uint64_t offset, std::uint64_t count,
                                               std::string_view what) {
  if (offset >= window_offset_ && count <= window_.size() &&
      offset - window_offset_ <= window_.size() - count) {
    return std::span<const std::uint8_t>(window_).subspan(offset - window_offset_, count);
  }
  constexpr std::uint64_t kReadAhead = std::uint64_t{1} << 20;
  if (offset > size_ || count > size_ - offset) read(offset, count, window_, what);  // throws
  window_offset_ = offset;
  (void)read_some(offset, count < kReadAhead ? kReadAhead : count, window_);
  return std::span<const std::uint8_t>(window_).first(count);
}

void ByteCursor::fail(const std::string& problem) const {
  throw_at_offset(*path_, offset(), context_.empty() ? problem : problem + " " + context_);
}

void ByteCursor::need(std::uint64_t count, std::string_view what) const {
  if (count <= remaining()) return;
  fail("truncated " + std::string(what) + ": it needs " + std::to_string(count) + " bytes, " +
       std::to_string(remaining()) + " are left");
}

std::uint8_t ByteCursor::u8(std::string_view what) {
  need(1, what);
  return bytes_[pos_++];
}
std::uint16_t ByteCursor::u16(std::string_view what) {
  need(2, what);
  const std::uint16_t v = load_le16(bytes_.data() + pos_);
  pos_ += 2;
  return v;
}
std::uint32_t ByteCursor::u32(std::string_view what) {
  need(4, what);
  const std::uint32_t v = load_le32(bytes_.data() + pos_);
  pos_ += 4;
  return v;
}
std::uint64_t ByteCursor::u64(std::string_view what) {
  need(8, what);
  const std::uint64_t v = load_le64(bytes_.data() + pos_);
  pos_ += 8;
  return v;
}
std::span<const std::uint8_t> ByteCursor::bytes(std::uint64_t count, std::string_view what) {
  need(count, what);
  const auto out = bytes_.subspan(pos_, static_cast<std::size_t>(count));
  pos_ += static_cast<std::size_t>(count);
  return out;
}
std::string_view ByteCursor::string32(std::string_view what) {
  const std::uint32_t length = u32(what);
  const auto b = bytes(length, what);
  return {reinterpret_cast<const char*>(b.data()), b.size()};
}

std::string printable_bytes(std::string_view text) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  std::size_t shown = 0;
  for (const char c : text) {
    if (++shown > 80) {
      out.append("...");
      break;
    }
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F && c != '\\' && c != '\'') {
      out.push_back(c);
    } else {
      out.append("\\x").push_back(kDigits[u >> 4]);
      out.push_back(kDigits[u & 0xFu]);
    }
  }
  return out;
}

std::string quoted_bytes(std::string_view text) {
  std::string out = "'";  // append only: GCC 12 warns falsely (-Wrestrict) on "'" + string
  out.append(printable_bytes(text)).push_back('\'');
  return out;
}

}  // namespace imunoise::io
