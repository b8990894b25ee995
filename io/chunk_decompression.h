/// @file
/// @brief Decompression of the chunks of ROS bags and MCAP files (internal to io/rosbag1_reader
/// and io/mcap_reader): bzip2 (libbz2), LZ4 frames (liblz4's LZ4F API; the format of rosbag's
/// roslz4 and of MCAP's "lz4") and Zstandard (libzstd). The output never grows past the size
/// the chunk declares, and grows with what the stream really yields (from a small first
/// allocation), so a corrupt declared size cannot make the reader allocate more than the data
/// decompresses to.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::io {

/// The compressions a chunk may use.
enum class ChunkCompression { kNone, kBz2, kLz4, kZstd };

/// "none", "bz2", "lz4", "zstd".
std::string_view chunk_compression_name(ChunkCompression compression);

/// The largest decompressed chunk accepted [bytes] (1 GiB; rosbag writes 768 KiB chunks, MCAP
/// writers a few MiB).
inline constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;

/// Decompresses IN, compressed with COMPRESSION (not kNone), into OUT, which must then hold
/// exactly DECLARED_SIZE bytes. Throws InputError "PATH: byte offset OFFSET: problem" when
/// DECLARED_SIZE is above kMaxChunkBytes, the stream is corrupt, ends early, or yields more or
/// fewer bytes than declared.
void decompress_chunk(ChunkCompression compression, std::span<const std::uint8_t> in,
                      std::uint64_t declared_size, std::vector<std::uint8_t>& out,
                      const std::string& path, std::uint64_t offset);

}  // namespace imunoise::io
