#include "io/atomic_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/errors.h"

namespace imunoise::io {

AtomicOutputFile::AtomicOutputFile(std::string target_path)
    : target_(std::move(target_path)),
      temp_(target_ + ".tmp." + std::to_string(static_cast<long>(::getpid()))) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw InputError(located_message(
        target_, 0, 0, std::string("cannot create output file (") + std::strerror(errno) + ")"));
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) {
    out_.close();
    std::remove(temp_.c_str());
  }
}

void AtomicOutputFile::commit() {
  out_.flush();
  const bool write_ok = static_cast<bool>(out_);
  out_.close();
  if (!write_ok || out_.fail()) {
    std::remove(temp_.c_str());
    committed_ = true;
    throw InputError(
        located_message(target_, 0, 0, "writing the output failed (disk full or I/O error)"));
  }
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temp_.c_str());
    committed_ = true;
    throw InputError(
        located_message(target_, 0, 0, "cannot move the output into place (" + reason + ")"));
  }
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  AtomicOutputFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

void create_output_directory(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) {
    throw InputError(path + ": cannot create the output directory: " + ec.message());
  }
  if (!std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": cannot create the output directory: a file of that name exists");
  }
}

}  // namespace imunoise::io
