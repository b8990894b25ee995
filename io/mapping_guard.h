/// @file
/// @brief Turns the SIGBUS of reading a file mapping whose file shrank under it into an error
/// the reader can report. A read-only mapping of a file that another process truncates while
/// we parse it faults on the pages past the new end: by default that kills the process. While
/// a MappingGuard is alive, such a fault inside its range maps a page of zeros there instead
/// (the read then sees NUL bytes) and marks the guard; the reader checks truncated() before it
/// trusts or reports anything it parsed. A SIGBUS outside every guarded range keeps its
/// previous disposition (the handler restores it, and the fault repeats).
#pragma once

#include <cstddef>

namespace imunoise::io {

class MappingGuard {
 public:
  /// Guards [BEGIN, BEGIN + SIZE), a mapping made by the caller. Throws std::runtime_error
  /// when all guard slots (64 per process) are taken or the handler cannot be installed.
  MappingGuard(const void* begin, std::size_t size);
  ~MappingGuard();
  MappingGuard(const MappingGuard&) = delete;
  MappingGuard& operator=(const MappingGuard&) = delete;

  /// True once a read inside the range faulted (the file is shorter than the mapping).
  bool truncated() const;

 private:
  std::size_t slot_;
};

}  // namespace imunoise::io
