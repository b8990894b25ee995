/// @file
/// @brief Shared by the fuzz targets (fuzz/CMakeLists.txt): a per-process scratch file for the
/// readers that take a path, and the one rule every target checks — only imunoise::InputError
/// and imunoise::AnalysisError may leave a reader; anything else aborts (a finding).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "common/errors.h"

namespace imunoise::fuzz {

/// Path of a scratch file for this process, in $TMPDIR (else /dev/shm, else /tmp); the file is
/// rewritten on every call and removed at exit.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& name) {
    const char* tmp = std::getenv("TMPDIR");
    std::string dir = tmp != nullptr && *tmp != '\0' ? tmp : "";
    if (dir.empty()) dir = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    path_ = dir + "/imunoise-fuzz-" + std::to_string(::getpid()) + "-" + name;
  }
  ~ScratchFile() { std::remove(path_.c_str()); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// Replaces the file's content with BYTES and returns its path.
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr) {
      std::perror(path_.c_str());
      std::abort();
    }
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    if (std::fclose(f) != 0) std::abort();
    return path_;
  }
  const std::string& write(std::string_view text) {
    return write(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Runs F; InputError and AnalysisError are the expected answers to hostile input and are
/// swallowed. Any other exception is reported and aborts, so libFuzzer keeps the input.
template <class F>
void expect_only_typed_errors(const char* what, F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const AnalysisError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FUZZ FINDING in %s: unexpected %s: %s\n", what, typeid(e).name(),
                 e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "FUZZ FINDING in %s: unexpected non-std exception\n", what);
    std::abort();
  }
}

/// A violated property (e.g. a round trip that changes the text): report and abort.
[[noreturn]] inline void property_failed(const char* what, const std::string& detail) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n%s\n", what, detail.c_str());
  std::abort();
}

}  // namespace imunoise::fuzz
