/// @file
/// @brief Reading of CDR-serialized ROS 2 messages (the payloads of rosbag2 .db3 files and of
/// MCAP channels with message encoding "cdr"): the 4-byte encapsulation header, then primitives
/// in the byte order it names, each aligned to its size relative to the start of the payload
/// after that header — at most 8 bytes in plain CDR (XCDR1, OMG DDS-XTypes 1.3 §7.4.3.4.2,
/// "CDR_BE"/"CDR_LE"), at most 4 in plain XCDR2 ("CDR2_BE"/"CDR2_LE", §7.4.3.4.3). Parameter-list
/// and delimited encodings (mutable or appendable types) are refused: ROS 2 messages are final.
///
/// Reads return false on bytes that run out or an unsupported header, with a message in
/// error(); the caller adds where (file, offset), so no exception is built per message.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace imunoise::io {

/// A cursor over one CDR message.
class CdrReader {
 public:
  /// Reads the encapsulation header of BYTES; ok() is false (error() says why) when it is
  /// missing or names an encoding other than plain CDR / XCDR2, little or big endian.
  explicit CdrReader(std::span<const std::uint8_t> bytes);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  bool big_endian() const { return big_endian_; }
  /// The bytes of the payload (after the header) not read yet.
  std::size_t remaining() const { return bytes_.size() - pos_; }

  bool read_u32(std::uint32_t& value, const char* what);
  bool read_i32(std::int32_t& value, const char* what);
  bool read_f64(double& value, const char* what);
  /// COUNT float64 values (a fixed-size array): into OUT, or skipped when OUT is null.
  bool read_f64s(double* out, std::size_t count, const char* what);
  /// A string (uint32 length counting the terminating NUL, then the bytes), skipped.
  bool skip_string(const char* what);

 private:
  bool align_and_need(std::size_t size, std::size_t count, const char* what);

  std::span<const std::uint8_t> bytes_;  // the payload after the encapsulation header
  std::size_t pos_ = 0;
  std::size_t max_align_ = 8;
  bool big_endian_ = false;
  std::string error_;
};

}  // namespace imunoise::io
