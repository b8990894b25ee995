/// @file
/// @brief Atomic output files: everything is written to a temporary file next to the target
/// and renamed over it only on commit(), so a failure never leaves a half-written output.
#pragma once

#include <fstream>
#include <string>

namespace imunoise::io {

/// Writes FILE through FILE.tmp.<pid>; commit() flushes, checks the stream and renames.
/// If the object is destroyed without commit() (an exception, an early return), the
/// temporary file is removed and the target is left untouched.
class AtomicOutputFile {
 public:
  /// Opens the temporary file; throws imunoise::InputError naming the path if it cannot.
  explicit AtomicOutputFile(std::string target_path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// The stream to write to.
  std::ostream& stream() { return out_; }

  /// Flushes, verifies no write failed (disk full …) and renames onto the target.
  /// Throws imunoise::InputError naming the path on failure.
  void commit();

  const std::string& target_path() const { return target_; }

 private:
  std::string target_;
  std::string temp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Convenience: atomically replaces PATH with CONTENT.
void write_file_atomically(const std::string& path, const std::string& content);

/// Creates the output directory PATH and its parents if needed. Throws imunoise::InputError
/// "PATH: cannot create the output directory: REASON" when it cannot (e.g. PATH or a parent is
/// an existing file, or permission is denied).
void create_output_directory(const std::string& path);

}  // namespace imunoise::io
