/// @file
/// @brief Opening and block reads of the CSV reader's streaming source (see line_source.h).
#include "io/line_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <system_error>

#include "common/errors.h"

namespace imunoise::io::csv_detail {

namespace {

std::string errno_text(int err) { return std::generic_category().message(err); }

}  // namespace

LineSource::LineSource(const std::string& path) : path_(path) {
  do {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  } while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0) {
    const int err = errno;
    std::string what = "cannot open: ";
    what.append(errno_text(err));
    if (err == ENOENT)
      what.append(" (check the path; relative paths start at the current directory)");
    throw InputError(located_message(path, 0, 0, what));
  }
  struct stat st {};
  if (::fstat(fd_, &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      ::close(fd_);
      fd_ = -1;
      throw InputError(located_message(path, 0, 0, "is a directory, not a data file"));
    }
    if (S_ISREG(st.st_mode)) size_hint_ = static_cast<std::size_t>(st.st_size);
  }
  buffer_.resize(kBlockBytes);
}

LineSource::~LineSource() {
  if (fd_ >= 0) ::close(fd_);
}

void LineSource::read_more() {
  if (pos_ > 0) {  // keep only the unconsumed tail (a partial line)
    std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
    end_ -= pos_;
    scan_ -= pos_;
    pos_ = 0;
  }
  if (end_ == buffer_.size()) {
    if (buffer_.size() >= kMaxLineBytes) {
      throw InputError(located_message(path_, line_number_ + 1, 0,
                                       "line longer than 16 MiB: not a numeric text table"));
    }
    buffer_.resize(buffer_.size() * 2);
  }
  ssize_t got = 0;
  do {
    got = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
  } while (got < 0 && errno == EINTR);
  if (got < 0) {
    throw InputError(
        located_message(path_, line_number_ + 1, 0, "cannot read: " + errno_text(errno)));
  }
  if (got == 0) {
    eof_ = true;
  } else {
    end_ += static_cast<std::size_t>(got);
    bytes_read_ += static_cast<std::size_t>(got);
    if (progress_ != nullptr && size_hint_ > 0) {
      report_progress(*progress_, "reading",
                      static_cast<std::int64_t>(std::min(bytes_read_, size_hint_)),
                      static_cast<std::int64_t>(size_hint_));
    }
  }
}

}  // namespace imunoise::io::csv_detail
