/// @file
/// @brief Users' own LCM message types, read at run time: the parser of LCM type-definition
/// files (the `.lcm` language lcm-gen reads) and the parsed types. The fingerprint of a type is
/// in lcm_fingerprint.h, the generic decoder of its messages in lcm_field_decoder.h, the
/// mapping of a user's IMU message onto imunoise's six channels in lcm_user_imu_decoder.h.
///
/// Supported language: `package a.b;`, several `struct NAME { … }` per file, members
/// `TYPE name;`, `TYPE a, b;`, `TYPE name[DIM]…[DIM];` (DIM an integer literal > 0 or an earlier
/// scalar integer member), `const TYPE NAME = VALUE, …;` (skipped: constants do not enter the
/// fingerprint), `//` and `/* */` comments. TYPE is a primitive (int8_t int16_t int32_t int64_t
/// byte float double string boolean) or a struct defined in the same file ("name" or
/// "package.name"). Not supported: structs from other files, recursive structs, enums.
///
/// Every problem in a definition is an InputError "FILE:LINE:COL: problem"; no input bytes
/// crash the parser.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::io {

/// LCM's primitive types.
enum class LcmPrimitive {
  kInt8,
  kInt16,
  kInt32,
  kInt64,
  kByte,
  kFloat,
  kDouble,
  kString,
  kBoolean
};

/// One array dimension of a member.
struct LcmDimension {
  /// Text as written ("3", "0x3", or a member name); it enters the fingerprint verbatim.
  std::string size_text;
  bool variable = false;        ///< the size is the value of an earlier member of the struct
  std::int64_t fixed_size = 0;  ///< constant dimension: its value
  std::size_t size_member = 0;  ///< variable dimension: index of the member holding the size
};

/// One member (field) of a struct.
struct LcmMember {
  std::string name;
  std::string type_name;                  ///< as written: "double", "vec3_t", "pkg.vec3_t"
  std::optional<LcmPrimitive> primitive;  ///< empty for a nested struct
  std::size_t struct_index = 0;           ///< nested struct: its index in LcmTypeFile::structs
  std::vector<LcmDimension> dimensions;   ///< empty for a scalar
  int line = 0;                           ///< 1-based line and column of the type name
  int column = 0;
};

/// One `struct` of a definition file.
struct LcmStructType {
  std::string package;  ///< the file's package ("" when none)
  std::string name;
  std::vector<LcmMember> members;
  int line = 0;
  /// "package.name", or "name" without a package.
  std::string full_name() const { return package.empty() ? name : package + "." + name; }
};

/// A parsed definition file.
struct LcmTypeFile {
  std::string path;  ///< as given (used in messages)
  std::vector<LcmStructType> structs;

  /// Index of the struct called `type_name` ("package.name" or "name"); an empty name picks
  /// the only struct of the file. Throws InputError naming the file and listing its structs.
  std::size_t find_struct(const std::string& type_name) const;
};

/// Parses the text of a definition file; `path` only names the file in messages.
LcmTypeFile parse_lcm_type_definition(std::string_view text, const std::string& path);

/// Reads and parses the definition file at `path` (at most 1 MiB).
LcmTypeFile read_lcm_type_definition(const std::string& path);

}  // namespace imunoise::io
