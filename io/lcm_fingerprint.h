/// @file
/// @brief The fingerprint of an LCM message type: computed from a parsed definition exactly as
/// lcm-gen's generated `T::getHash()` computes it (lcmgen.c: hash_update, hash_string,
/// lcm_struct_hash, and the generated _computeHash), and its text form in messages. Every
/// encoded LCM message starts with the 8-byte big-endian fingerprint of its type, which is how
/// the log reader and the decoders recognise a type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/lcm_type_definition.h"

namespace imunoise::io {

/// The fingerprint of struct `struct_index` of `file`: the value of lcm-gen's `T::getHash()`
/// and the first 8 bytes (big-endian) of every encoded message of that type. Hashes member
/// names, primitive type names and dimensions (not the struct name, not constants), plus the
/// fingerprint of every nested struct type.
std::uint64_t lcm_fingerprint(const LcmTypeFile& file, std::size_t struct_index);

/// "0x" and 16 lower-case hex digits, as fingerprints are shown in messages.
std::string lcm_fingerprint_text(std::uint64_t fingerprint);

}  // namespace imunoise::io
