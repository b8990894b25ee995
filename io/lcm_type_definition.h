/// @file
/// @brief Users' own LCM message types, read at run time: a parser of LCM type-definition files
/// (the `.lcm` language lcm-gen reads), the type fingerprint exactly as lcm-gen's generated
/// `T::getHash()` computes it, a generic decoder of encoded messages, and the mapping of a
/// user's IMU message onto imunoise's six channels (`LcmUserType`, used by read_lcm_imu_log).
///
/// Supported language: `package a.b;`, several `struct NAME { … }` per file, members
/// `TYPE name;`, `TYPE a, b;`, `TYPE name[DIM]…[DIM];` (DIM an integer literal > 0 or an earlier
/// scalar integer member), `const TYPE NAME = VALUE, …;` (skipped: constants do not enter the
/// fingerprint), `//` and `/* */` comments. TYPE is a primitive (int8_t int16_t int32_t int64_t
/// byte float double string boolean) or a struct defined in the same file ("name" or
/// "package.name"). Not supported: structs from other files, recursive structs, enums.
///
/// Every problem in a definition is an InputError "FILE:LINE:COL: problem"; no input bytes
/// crash the parser. Decoding never throws: a malformed message is a `false` return with the
/// problem as text, and every length is checked against the bytes left before it is used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/imu_samples.h"

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

/// The fingerprint of struct `struct_index`: the value of lcm-gen's `T::getHash()` and the
/// first 8 bytes (big-endian) of every encoded message of that type.
std::uint64_t lcm_fingerprint(const LcmTypeFile& file, std::size_t struct_index);

/// One decoded leaf of a message (LcmFieldDecoder::decode_all).
struct LcmFieldValue {
  /// "name", "name[i]", "name[i][j]", nested "outer.inner[i]", "history[2].v[0]".
  std::string path;
  LcmPrimitive type = LcmPrimitive::kDouble;
  double value = 0.0;        ///< numeric types as double (strings: 0)
  std::int64_t integer = 0;  ///< exact value of integer types, byte and boolean (others: 0)
  std::string text;          ///< strings (without the terminating NUL)
};

/// Values of the selected fields of one message, one entry per slot (LcmFieldDecoder::decode).
struct LcmSlotValues {
  std::vector<double> values;
  /// The exact value when the slot's field has an integer type (int8_t … int64_t, byte,
  /// boolean), so int64 nanosecond stamps stay exact; 0 for float and double slots.
  std::vector<std::int64_t> integers;
};

/// Generic decoder of one struct of a definition file. Ask for the fields once (add_field:
/// each path resolves to slots), then decode each message into slot values without building
/// names. Not thread-safe (it reuses scratch space); use one decoder per thread.
class LcmFieldDecoder {
 public:
  LcmFieldDecoder(LcmTypeFile file, std::size_t struct_index);

  /// Selects the numeric field at `path` ("gyro[1]", "imu.accel[2]", "grid[1][0]") and returns
  /// its slot; a fixed-size 1-D array named whole ("gyro" for `double gyro[3]`) selects every
  /// element, one slot each, in order (at most 4096 elements; a larger array is an InputError
  /// asking for its elements by index). Throws InputError when the path names no numeric field
  /// (unknown member — the message lists the struct's members —, string, struct, wrong number
  /// of indices, index beyond a fixed dimension).
  std::vector<std::size_t> add_field(const std::string& path);

  std::size_t slot_count() const { return slot_paths_.size(); }
  /// The element path of a slot ("gyro[0]").
  const std::string& slot_path(std::size_t slot) const { return slot_paths_.at(slot); }
  LcmPrimitive slot_type(std::size_t slot) const { return slot_types_.at(slot); }

  std::uint64_t fingerprint() const { return fingerprint_; }
  const LcmTypeFile& file() const { return file_; }
  const LcmStructType& type() const { return file_.structs[struct_index_]; }

  /// Decodes one encoded message (its 8-byte fingerprint first) into `out` (resized to
  /// slot_count()). False, with the problem in `error` ("byte N: …"), when the fingerprint
  /// differs, the bytes end early or are left over, a length is negative or beyond the
  /// message, or a selected element is beyond a variable-length array in this message.
  bool decode(std::span<const unsigned char> message, LcmSlotValues& out, std::string& error);

  /// Decodes every leaf of one message, named, in encoding order (strings included). Same
  /// failures as decode().
  bool decode_all(std::span<const unsigned char> message, std::vector<LcmFieldValue>& out,
                  std::string& error);

 private:
  // The selection tree: which elements of which members feed which slot. A node describes the
  // selection inside one struct instance; nodes_[0] is the top-level struct.
  struct ElementPick {                // one selected element of a primitive member
    std::vector<std::int64_t> index;  // one index per dimension (empty for a scalar)
    std::size_t slot = 0;
  };
  struct ElementNode {  // one selected element of a nested-struct member
    std::vector<std::int64_t> index;
    std::size_t node = 0;
  };
  struct MemberSelection {
    std::vector<ElementPick> leaves;
    std::vector<ElementNode> elements;
  };
  struct SelectionNode {
    std::vector<MemberSelection> members;  // parallel to the struct's members
  };
  class Walker;  // the decoding pass (lcm_type_definition.cpp)

  std::size_t node_for(std::size_t parent_node, std::size_t member,
                       const std::vector<std::int64_t>& index, std::size_t struct_index);

  LcmTypeFile file_;
  std::size_t struct_index_ = 0;
  std::uint64_t fingerprint_ = 0;
  std::vector<std::uint64_t> min_encoded_bytes_;  // per struct of file_
  std::vector<SelectionNode> nodes_;
  std::vector<std::string> slot_paths_;
  std::vector<LcmPrimitive> slot_types_;
  std::vector<std::int64_t> scratch_;  // integer members of the struct instances being decoded
};

/// A user's own IMU message type, for read_lcm_imu_log (LcmReadOptions::user_type).
struct LcmUserType {
  std::string definition_path;  ///< the `.lcm` file defining the type
  std::string type_name;        ///< struct to use ("pkg.name" or "name"); empty = the only one
  /// Field holding the sample stamp and its unit in seconds (1e-6 µs, 1e-9 ns, 1 s). The stamp
  /// becomes integer µs = llround(value × time_unit_s × 1e6); integer fields are converted
  /// exactly when the unit is an integer multiple or fraction of 1 µs (e.g. int64 ns).
  std::string time_field = "utime";
  double time_unit_s = 1e-6;
  /// One name of a numeric array of 3 (x, y, z), or three names of numeric fields. Both are
  /// required.
  std::vector<std::string> gyro_fields, accel_fields;
  /// Factors to SI: the field's unit in rad/s (rad for increments) and m/s² (m/s), e.g.
  /// π/180 for deg/s, 9.80665 for g.
  double gyro_scale_to_si = 1.0, accel_scale_to_si = 1.0;
  bool increments = false;  ///< the fields are angle / velocity increments per sample
};

/// Decodes a user's IMU messages into ImuSampleColumns (SI, stamps in µs).
class LcmUserImuDecoder {
 public:
  /// Reads the definition and resolves the fields; throws InputError for a bad definition,
  /// an unknown struct or field, fewer or more than 3 gyro or accel values, a bad unit or scale.
  explicit LcmUserImuDecoder(const LcmUserType& user_type);

  std::uint64_t fingerprint() const { return decoder_.fingerprint(); }
  /// "package.name" of the struct used.
  std::string type_name() const { return decoder_.type().full_name(); }
  const std::string& definition_path() const { return definition_path_; }

  /// Empty columns carrying the increments flag and the source fields and units.
  ImuSampleColumns make_columns() const;

  /// Decodes one message and appends it to `samples`. A NaN/Inf among the used fields drops
  /// the message (counted in `samples`) when `drop_non_finite`, else fails. False, with the
  /// problem in `error`, when the message does not decode, has a non-finite value (and
  /// !drop_non_finite) or a stamp beyond the int64 µs range.
  bool append(std::span<const unsigned char> message, bool drop_non_finite,
              ImuSampleColumns& samples, std::string& error);

 private:
  bool stamp_us(std::int64_t* out, std::string& error) const;

  std::string definition_path_;
  LcmFieldDecoder decoder_;
  std::size_t time_slot_ = 0;
  std::size_t value_slots_[6] = {};
  double scale_to_si_[6] = {};
  double time_unit_s_ = 1e-6;
  bool increments_ = false;
  LcmSlotValues slot_values_;
};

}  // namespace imunoise::io
