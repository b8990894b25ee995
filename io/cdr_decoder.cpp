/// @file
/// @brief CDR message reading (see cdr_decoder.h).
#include "io/cdr_decoder.h"

#include <bit>
#include <cstring>

namespace imunoise::io {
namespace {

// Encapsulation identifiers (the first two bytes, big-endian), DDS-XTypes 1.3 Table 60 and
// DDS-RTPS 2.5 §10.
constexpr std::uint16_t kCdrBe = 0x0000;
constexpr std::uint16_t kCdrLe = 0x0001;
constexpr std::uint16_t kCdr2Be = 0x0006;
constexpr std::uint16_t kCdr2Le = 0x0007;

std::string hex16(std::uint16_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) out.push_back(kDigits[(v >> shift) & 0xFu]);
  return out;
}

template <typename T>
T load(const std::uint8_t* p, bool big_endian) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    if constexpr (sizeof(T) == 4) {
      std::uint32_t u = std::bit_cast<std::uint32_t>(value);
      u = __builtin_bswap32(u);
      value = std::bit_cast<T>(u);
    } else {
      std::uint64_t u = std::bit_cast<std::uint64_t>(value);
      u = __builtin_bswap64(u);
      value = std::bit_cast<T>(u);
    }
  }
  return value;
}

}  // namespace

CdrReader::CdrReader(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < 4) {
    error_ = "a " + std::to_string(bytes.size()) +
             "-byte message, shorter than the 4-byte CDR encapsulation header";
    return;
  }
  const auto id = static_cast<std::uint16_t>((bytes[0] << 8) | bytes[1]);
  switch (id) {
    case kCdrBe:
    case kCdrLe:
      max_align_ = 8;
      break;
    case kCdr2Be:
    case kCdr2Le:
      max_align_ = 4;
      break;
    default:
      error_ = "CDR encapsulation " + hex16(id) +
               " is not supported (expected plain CDR or XCDR2, 0x0000/0x0001/0x0006/0x0007)";
      return;
  }
  big_endian_ = id == kCdrBe || id == kCdr2Be;
  bytes_ = bytes.subspan(4);
}

bool CdrReader::align_and_need(std::size_t size, std::size_t count, const char* what) {
  if (!ok()) return false;
  const std::size_t align = size < max_align_ ? size : max_align_;
  const std::size_t pad = (align - pos_ % align) % align;
  if (pad > remaining() || count > (remaining() - pad) / size) {
    error_ = std::string("truncated CDR message: ") + what + " needs " +
             std::to_string(pad + count * size) + " bytes at payload offset " +
             std::to_string(pos_) + ", " + std::to_string(remaining()) + " are left";
    return false;
  }
  pos_ += pad;
  return true;
}

bool CdrReader::read_u32(std::uint32_t& value, const char* what) {
  if (!align_and_need(4, 1, what)) return false;
  value = load<std::uint32_t>(bytes_.data() + pos_, big_endian_);
  pos_ += 4;
  return true;
}

bool CdrReader::read_i32(std::int32_t& value, const char* what) {
  std::uint32_t u = 0;
  if (!read_u32(u, what)) return false;
  value = static_cast<std::int32_t>(u);
  return true;
}

bool CdrReader::read_f64(double& value, const char* what) { return read_f64s(&value, 1, what); }

bool CdrReader::read_f64s(double* out, std::size_t count, const char* what) {
  if (!align_and_need(8, count, what)) return false;
  if (out != nullptr) {
    for (std::size_t i = 0; i < count; ++i) {
      out[i] = load<double>(bytes_.data() + pos_ + 8 * i, big_endian_);
    }
  }
  pos_ += 8 * count;
  return true;
}

bool CdrReader::skip_string(const char* what) {
  std::uint32_t length = 0;
  if (!read_u32(length, what)) return false;
  if (length > remaining()) {
    error_ = std::string("truncated CDR message: ") + what + " has length " +
             std::to_string(length) + ", " + std::to_string(remaining()) + " bytes are left";
    return false;
  }
  pos_ += length;
  return true;
}

}  // namespace imunoise::io
