/// @file
/// @brief LCM type fingerprints as lcm-gen computes them (see lcm_fingerprint.h).
#include "io/lcm_fingerprint.h"

#include <optional>
#include <string_view>
#include <vector>

namespace imunoise::io {
namespace {

// Fingerprint (lcmgen.c: hash_update, hash_string, lcm_struct_hash; the generated
// _computeHash). lcm-gen hashes with int64 and a plain char, i.e. an arithmetic right shift and
// a signed byte on the platforms it ships for.

std::uint64_t hash_update(std::uint64_t v, signed char c) {
  const auto arithmetic_shift = static_cast<std::uint64_t>(static_cast<std::int64_t>(v) >> 55);
  return ((v << 8) ^ arithmetic_shift) + static_cast<std::uint64_t>(std::int64_t{c});
}

std::uint64_t hash_string(std::uint64_t v, std::string_view s) {
  v = hash_update(v, static_cast<signed char>(s.size()));
  for (const char c : s) v = hash_update(v, static_cast<signed char>(c));
  return v;
}

/// lcm_struct_hash: member names, primitive type names and dimensions; not the struct name.
std::uint64_t struct_base_hash(const LcmStructType& s) {
  std::uint64_t v = 0x12345678;
  for (const LcmMember& m : s.members) {
    v = hash_string(v, m.name);
    if (m.primitive) v = hash_string(v, m.type_name);
    v = hash_update(v, static_cast<signed char>(m.dimensions.size()));
    for (const LcmDimension& d : m.dimensions) {
      v = hash_update(v, d.variable ? 1 : 0);
      v = hash_string(v, d.size_text);
    }
  }
  return v;
}

/// _computeHash: base + the hash of every nested member's type, then rotated left by one.
/// (Its "already among the parents → 0" case cannot occur: recursive types are refused, so
/// each struct's hash is the same wherever it appears and can be memoized.)
std::uint64_t computed_hash(const LcmTypeFile& file, std::size_t index,
                            std::vector<std::optional<std::uint64_t>>& memo) {
  if (memo[index]) return *memo[index];
  std::uint64_t hash = struct_base_hash(file.structs[index]);
  for (const LcmMember& m : file.structs[index].members) {
    if (!m.primitive) hash += computed_hash(file, m.struct_index, memo);
  }
  const std::uint64_t rotated = (hash << 1) + ((hash >> 63) & 1);
  memo[index] = rotated;
  return rotated;
}
}  // namespace

std::uint64_t lcm_fingerprint(const LcmTypeFile& file, std::size_t struct_index) {
  std::vector<std::optional<std::uint64_t>> memo(file.structs.size());
  return computed_hash(file, struct_index, memo);
}

std::string lcm_fingerprint_text(std::uint64_t fingerprint) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "0x";
  for (int shift = 60; shift >= 0; shift -= 4)
    out.push_back(kDigits[(fingerprint >> shift) & 0xFu]);
  return out;
}

}  // namespace imunoise::io
