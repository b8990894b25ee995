/// @file
/// @brief Internal to the LCM type modules (lcm_type_definition, lcm_fingerprint,
/// lcm_field_decoder, lcm_user_imu_decoder): facts about LCM's primitive types and the bounds
/// the parser enforces and the decoder relies on. Not part of the public API.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "io/lcm_type_definition.h"

namespace imunoise::io::detail {

/// Most array dimensions of one member. Far beyond any real message type; the bound keeps the
/// decoder's per-member dimension array small.
inline constexpr std::size_t kMaxDimensions = 16;
/// Deepest nesting of structs the parser accepts; it bounds the decoder's recursion.
inline constexpr int kMaxNestingDepth = 32;

/// One primitive type: its name in a definition and its encoded size.
struct PrimitiveInfo {
  const char* name;
  LcmPrimitive type;
  std::uint64_t bytes;  ///< encoded size; strings: the minimum (int32 length + NUL)
};

/// Indexed by LcmPrimitive.
inline constexpr std::array<PrimitiveInfo, 9> kPrimitives{{
    {"int8_t", LcmPrimitive::kInt8, 1},
    {"int16_t", LcmPrimitive::kInt16, 2},
    {"int32_t", LcmPrimitive::kInt32, 4},
    {"int64_t", LcmPrimitive::kInt64, 8},
    {"byte", LcmPrimitive::kByte, 1},
    {"float", LcmPrimitive::kFloat, 4},
    {"double", LcmPrimitive::kDouble, 8},
    {"string", LcmPrimitive::kString, 5},
    {"boolean", LcmPrimitive::kBoolean, 1},
}};

inline const PrimitiveInfo& primitive_info(LcmPrimitive type) {
  return kPrimitives[static_cast<std::size_t>(type)];
}

/// The primitive type spelt `name` ("double"), or nullopt for any other name.
inline std::optional<LcmPrimitive> primitive_named(std::string_view name) {
  for (const PrimitiveInfo& p : kPrimitives) {
    if (name == p.name) return p.type;
  }
  return std::nullopt;
}

/// The types an array size may have (lcm-gen refuses byte and boolean).
inline bool is_size_type(LcmPrimitive t) {
  return t == LcmPrimitive::kInt8 || t == LcmPrimitive::kInt16 || t == LcmPrimitive::kInt32 ||
         t == LcmPrimitive::kInt64;
}

/// The types whose values are exact integers (int8_t … int64_t, byte, boolean).
inline bool is_integer_valued(LcmPrimitive t) {
  return t != LcmPrimitive::kFloat && t != LcmPrimitive::kDouble && t != LcmPrimitive::kString;
}

/// A C identifier: [A-Za-z_][A-Za-z0-9_]* (member, struct and package names, field paths).
inline bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  const auto alpha = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  if (!alpha(s.front())) return false;
  return std::all_of(s.begin(), s.end(),
                     [&](char c) { return alpha(c) || (c >= '0' && c <= '9'); });
}

}  // namespace imunoise::io::detail
