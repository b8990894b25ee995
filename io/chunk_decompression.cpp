/// @file
/// @brief Chunk decompression (see chunk_decompression.h). Each codec runs its streaming API
/// into an output that doubles while the stream still yields bytes, capped at the declared
/// size.
#include "io/chunk_decompression.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <climits>
#include <memory>

#include "common/errors.h"
#include "io/binary_file.h"

namespace imunoise::io {
namespace {

/// The output buffer: starts small, doubles on demand, never past the declared size.
class GrowingOutput {
 public:
  GrowingOutput(std::vector<std::uint8_t>& out, std::uint64_t declared, std::size_t in_size)
      : out_(out), cap_(static_cast<std::size_t>(declared) + 1) {
    // One byte beyond the declared size, so that a stream yielding more is seen as such.
    const std::size_t first = std::min<std::size_t>(cap_, in_size * 4 + 65536);
    out_.resize(first);
  }
  /// Room after the bytes produced so far; grows the buffer when full. Returns false when the
  /// stream has yielded more than the declared size.
  bool make_room() {
    if (produced_ < out_.size()) return true;
    if (out_.size() >= cap_) return false;
    out_.resize(std::min<std::size_t>(cap_, std::max<std::size_t>(out_.size() * 2, 1)));
    return true;
  }
  std::uint8_t* next() { return out_.data() + produced_; }
  std::size_t room() const { return out_.size() - produced_; }
  void produced(std::size_t n) { produced_ += n; }
  std::size_t total() const { return produced_; }
  void finish() { out_.resize(produced_); }

 private:
  std::vector<std::uint8_t>& out_;
  std::size_t cap_;
  std::size_t produced_ = 0;
};

struct Context {
  const std::string& path;
  std::uint64_t offset;
  std::string_view codec;
  std::uint64_t declared;

  [[noreturn]] void fail(const std::string& problem) const {
    throw_at_offset(path, offset, std::string(codec) + " chunk: " + problem);
  }
  [[noreturn]] void too_long() const {
    fail("decompresses to more than the " + std::to_string(declared) + " bytes it declares");
  }
};

void bz2(std::span<const std::uint8_t> in, GrowingOutput& out, const Context& cx) {
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) cx.fail("cannot initialise libbz2");
  const auto end = [](bz_stream* p) { BZ2_bzDecompressEnd(p); };
  std::unique_ptr<bz_stream, decltype(end)> guard(&s, end);
  std::size_t consumed = 0;
  for (;;) {
    if (!out.make_room()) cx.too_long();
    const std::size_t in_step = std::min<std::size_t>(in.size() - consumed, UINT_MAX);
    const std::size_t out_step = std::min<std::size_t>(out.room(), UINT_MAX);
    s.next_in = const_cast<char*>(reinterpret_cast<const char*>(in.data() + consumed));
    s.avail_in = static_cast<unsigned>(in_step);
    s.next_out = reinterpret_cast<char*>(out.next());
    s.avail_out = static_cast<unsigned>(out_step);
    const int rc = BZ2_bzDecompress(&s);
    consumed += in_step - s.avail_in;
    out.produced(out_step - s.avail_out);
    if (rc == BZ_STREAM_END) return;
    if (rc != BZ_OK) cx.fail("corrupt bzip2 data (libbz2 error " + std::to_string(rc) + ")");
    if (consumed == in.size() && s.avail_out != 0) cx.fail("the bzip2 stream ends early");
  }
}

void lz4(std::span<const std::uint8_t> in, GrowingOutput& out, const Context& cx) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    cx.fail("cannot initialise liblz4");
  }
  const auto end = [](LZ4F_dctx* p) { LZ4F_freeDecompressionContext(p); };
  std::unique_ptr<LZ4F_dctx, decltype(end)> dctx(raw, end);
  std::size_t consumed = 0;
  std::size_t hint = 1;
  while (consumed < in.size()) {
    if (!out.make_room()) cx.too_long();
    std::size_t in_step = in.size() - consumed;
    std::size_t out_step = out.room();
    hint =
        LZ4F_decompress(dctx.get(), out.next(), &out_step, in.data() + consumed, &in_step, nullptr);
    if (LZ4F_isError(hint)) {
      cx.fail(std::string("corrupt LZ4 frame (") + LZ4F_getErrorName(hint) + ")");
    }
    consumed += in_step;
    out.produced(out_step);
    if (in_step == 0 && out_step == 0 && out.room() > 0) cx.fail("the LZ4 frame makes no progress");
  }
  // Input used up: flush what the context still holds.
  while (hint != 0) {
    if (!out.make_room()) cx.too_long();
    std::size_t in_step = 0;
    std::size_t out_step = out.room();
    hint = LZ4F_decompress(dctx.get(), out.next(), &out_step, nullptr, &in_step, nullptr);
    if (LZ4F_isError(hint)) {
      cx.fail(std::string("corrupt LZ4 frame (") + LZ4F_getErrorName(hint) + ")");
    }
    out.produced(out_step);
    if (out_step == 0 && hint != 0) cx.fail("the LZ4 frame ends early");
  }
}

void zstd(std::span<const std::uint8_t> in, GrowingOutput& out, const Context& cx) {
  const auto end = [](ZSTD_DStream* p) { ZSTD_freeDStream(p); };
  std::unique_ptr<ZSTD_DStream, decltype(end)> ds(ZSTD_createDStream(), end);
  if (!ds) cx.fail("cannot initialise libzstd");
  // Refuse windows above 128 MiB (ZSTD_WINDOWLOG_LIMIT_DEFAULT is 2^27): a forged frame header
  // must not make libzstd allocate a huge window.
  ZSTD_DCtx_setParameter(ds.get(), ZSTD_d_windowLogMax, 27);
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  std::size_t rc = 1;
  while (input.pos < input.size) {
    if (!out.make_room()) cx.too_long();
    ZSTD_outBuffer output{out.next(), out.room(), 0};
    rc = ZSTD_decompressStream(ds.get(), &output, &input);
    if (ZSTD_isError(rc)) {
      cx.fail(std::string("corrupt Zstandard data (") + ZSTD_getErrorName(rc) + ")");
    }
    out.produced(output.pos);
  }
  while (rc != 0) {
    if (!out.make_room()) cx.too_long();
    ZSTD_outBuffer output{out.next(), out.room(), 0};
    rc = ZSTD_decompressStream(ds.get(), &output, &input);
    if (ZSTD_isError(rc)) {
      cx.fail(std::string("corrupt Zstandard data (") + ZSTD_getErrorName(rc) + ")");
    }
    out.produced(output.pos);
    if (output.pos == 0 && rc != 0) cx.fail("the Zstandard frame ends early");
  }
}

}  // namespace

std::string_view chunk_compression_name(ChunkCompression compression) {
  switch (compression) {
    case ChunkCompression::kNone:
      return "none";
    case ChunkCompression::kBz2:
      return "bz2";
    case ChunkCompression::kLz4:
      return "lz4";
    case ChunkCompression::kZstd:
      return "zstd";
  }
  return "?";
}

void decompress_chunk(ChunkCompression compression, std::span<const std::uint8_t> in,
                      std::uint64_t declared_size, std::vector<std::uint8_t>& out,
                      const std::string& path, std::uint64_t offset) {
  IMUNOISE_EXPECT(compression != ChunkCompression::kNone,
                  "decompress_chunk: an uncompressed chunk needs no decompression");
  const Context cx{path, offset, chunk_compression_name(compression), declared_size};
  if (declared_size > kMaxChunkBytes) {
    cx.fail("declared size of " + std::to_string(declared_size) + " bytes is above the limit of " +
            std::to_string(kMaxChunkBytes));
  }
  GrowingOutput output(out, declared_size, in.size());
  switch (compression) {
    case ChunkCompression::kBz2:
      bz2(in, output, cx);
      break;
    case ChunkCompression::kLz4:
      lz4(in, output, cx);
      break;
    case ChunkCompression::kZstd:
      zstd(in, output, cx);
      break;
    case ChunkCompression::kNone:
      break;
  }
  if (output.total() > declared_size) cx.too_long();
  output.finish();
  if (output.total() != declared_size) {
    cx.fail("decompresses to " + std::to_string(output.total()) + " bytes, it declares " +
            std::to_string(declared_size));
  }
}

}  // namespace imunoise::io
