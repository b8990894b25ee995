/// @file
/// @brief FFTW wisdom import and atomic export (see fftw_wisdom.h).
#include "io/fftw_wisdom.h"

#include <fftw3.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>

#include "common/errors.h"
#include "common/fftw_planner_lock.h"
#include "io/atomic_output.h"

namespace imunoise::io {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

struct MallocFree {
  void operator()(char* p) const { std::free(p); }  // fftw_export_wisdom_to_string: free()
};

}  // namespace

void import_fftw_wisdom(const std::string& path) {
  // Opened here rather than by fftw_import_wisdom_from_filename, which answers 0 for every
  // failure: a file that cannot be opened and a file that is not wisdom are different fixes.
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "r"));
  if (!file) {
    const int error = errno;
    throw InputError(located_message(
        path, 0, 0,
        std::string("cannot open the FFTW wisdom file (") + std::strerror(error) + ")"));
  }
  int imported = 0;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    errno = 0;
    imported = fftw_import_wisdom_from_file(file.get());
  }
  if (imported != 0) return;
  if (std::ferror(file.get())) {
    const int error = errno;
    throw InputError(located_message(path, 0, 0,
                                     std::string("cannot read the FFTW wisdom file (") +
                                         std::strerror(error != 0 ? error : EIO) + ")"));
  }
  throw InputError(located_message(
      path, 0, 0,
      "not an FFTW wisdom file, or wisdom of another FFTW version or precision (make it with "
      "'imunoise fftw-wisdom')"));
}

void export_fftw_wisdom(const std::string& path) {
  std::unique_ptr<char, MallocFree> text;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    text.reset(fftw_export_wisdom_to_string());
  }
  if (!text) throw std::bad_alloc();
  write_file_atomically(path, text.get());
}

}  // namespace imunoise::io
