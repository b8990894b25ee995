/// @file
/// @brief The compact binary recording format (`.imnb`, docs/binary-format.md): a fixed
/// preamble, a JSON header with the recording's metadata (keys carry units), then one
/// 64-byte-aligned little-endian float64 array per column (time_s first, when present, then the
/// channels). Read by mmap at near memcpy speed; written atomically (io/atomic_output.h),
/// column by column, never the whole file in memory.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/progress_callback.h"
#include "common/version.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// @name Layout constants (docs/binary-format.md)
/// @{
/// File magic: a byte that can start neither UTF-8 text nor an LCM log (0xEDA1DA01), then
/// "IMNB", then CR LF and ^Z so text-mode transfers that mangle line ends are caught.
inline constexpr std::array<unsigned char, 8> kBinaryMagic{0x89, 'I',  'M',  'N',
                                                           'B',  '\r', '\n', 0x1A};
inline constexpr std::uint32_t kBinaryFormatVersion = 1;
/// magic (8) + version (u32) + reserved (u32, 0) + JSON header length (u64).
inline constexpr std::uint64_t kBinaryPreambleBytes = 24;
/// Every column (and so the first data byte) starts at a multiple of this file offset.
inline constexpr std::uint64_t kBinaryAlignment = 64;
/// Largest JSON header accepted [bytes] (a thousand channels need about 200 kB).
inline constexpr std::uint64_t kBinaryMaxHeaderBytes = 16u << 20;
/// Output extension that selects this format.
inline constexpr std::string_view kBinaryRecordingExtension = ".imnb";
/// The `created_by` value this build writes (the version `imunoise --version` prints).
inline constexpr std::string_view kBinaryCreatedBy = kSoftwareVersion;
/// @}

/// Everything in a binary recording but the sample values.
struct BinaryRecordingHeader {
  std::string source_path;        ///< the file the recording was converted from
  std::string created_by;         ///< "imunoise VERSION"
  double sample_period_s = 0.0;   ///< nominal Δt [s] (> 0, finite)
  std::optional<double> rate_hz;  ///< the given fixed rate [Hz]; present iff !has_time
  double start_time_s = 0.0;      ///< first time stamp as written in the source [s]
  std::uint64_t sample_count = 0;
  bool has_time = false;                    ///< a time_s column precedes the channels
  std::vector<pipeline::Channel> channels;  ///< names, units and provenance; `values` left empty
  std::int64_t non_finite_dropped =
      0;                          ///< as pipeline::SamplingReport (carried over from the source)
  std::int64_t rows_dropped = 0;  ///< as pipeline::SamplingReport

  /// Float64 columns in the data section: the channels plus time_s when present.
  std::size_t column_count() const { return channels.size() + (has_time ? 1 : 0); }
};

/// The header describing `recording` (created_by = kBinaryCreatedBy).
BinaryRecordingHeader binary_header_of(const pipeline::Recording& recording);

/// File offsets of the data section, computed overflow-safely from a header; nullopt when the
/// sizes do not fit in 64 bits.
struct BinaryLayout {
  std::uint64_t data_offset = 0;    ///< first column's offset (64-aligned)
  std::uint64_t column_stride = 0;  ///< bytes from one column to the next (64-aligned)
  std::uint64_t file_size = 0;      ///< exact size of a valid file

  std::uint64_t column_offset(std::size_t column) const {
    return data_offset + column_stride * column;
  }
};
std::optional<BinaryLayout> binary_layout(std::uint64_t header_bytes, std::uint64_t sample_count,
                                          std::uint64_t column_count);

/// Streams a binary recording to PATH through an AtomicOutputFile: the header is written at
/// construction, then each column's samples in order (columns in any order, any block size),
/// and commit() checks every column is complete, writes the padding and renames into place.
/// Destroyed without commit(), it leaves no file. Non-finite values are refused.
class BinaryRecordingWriter {
 public:
  /// Throws InputError naming PATH for an invalid header (as the reader would reject it) or a
  /// file that cannot be created.
  BinaryRecordingWriter(std::string path, BinaryRecordingHeader header);
  ~BinaryRecordingWriter();
  BinaryRecordingWriter(const BinaryRecordingWriter&) = delete;
  BinaryRecordingWriter& operator=(const BinaryRecordingWriter&) = delete;

  /// Appends VALUES to column COLUMN (0 = time_s when has_time, then the channels).
  void append(std::size_t column, std::span<const double> values);
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes RECORDING (all fields, time_s when not empty) to PATH atomically. Throws InputError
/// naming PATH for no channels, channels of different lengths, an invalid name or unit, a
/// non-finite value, or a write failure (no file is left behind).
void write_binary_recording(const std::string& path, const pipeline::Recording& recording);

/// True when PATH starts with kBinaryMagic.
bool is_binary_recording_file(const std::string& path);

/// Reads and validates only the preamble and JSON header of PATH (sizes checked against the
/// file size). Throws InputError "PATH: byte N: problem" or "PATH: header key K: problem".
BinaryRecordingHeader read_binary_header(const std::string& path);

/// Options of read_binary_recording.
struct BinaryReadOptions {
  /// |rate| at or beyond this counts as saturated in the sampling report [rad/s]
  std::optional<double> gyro_full_scale_rad_per_s;
  /// |specific force| at or beyond this counts as saturated [m/s²]
  std::optional<double> accel_full_scale_m_per_s2;
  /// Threads reading the columns and running the sampling checks (0 = all cores). The result
  /// does not depend on it.
  unsigned threads = 0;
};

/// Reads a binary recording: the whole header is validated before any data is touched (an
/// absurd sample_count fails the size check before any allocation), then the columns are read
/// in parallel with pread straight into the Recording (no mapping, so the peak memory is the
/// data size, and a file truncated during the read is an InputError, not a SIGBUS). A NaN/Inf value
/// is an InputError naming the column and sample index (binary recordings hold finite values only;
/// there is no drop option). The sampling report is built as read_recording does: from time_s
/// (non-monotonic stamps reported, not fatal; stamps that never increase are an error), or for the
/// fixed rate. Sample locations have no file line. `source_path` of the result is PATH. PROGRESS
/// (optional) gets
/// ("reading", bytes copied, data bytes).
pipeline::Recording read_binary_recording(const std::string& path,
                                          const BinaryReadOptions& options = {},
                                          const ProgressCallback& progress = {});

}  // namespace imunoise::io
