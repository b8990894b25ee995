/// @file
/// @brief The generic decoder of encoded LCM messages of a type read at run time
/// (lcm_type_definition.h): select numeric fields by path once, then decode each message into
/// one value per selected slot, or decode every leaf with its name.
///
/// Decoding never throws: a malformed message is a `false` return with the problem as text,
/// and every length is checked against the bytes left before it is used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/lcm_type_definition.h"

namespace imunoise::io {

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
  class Walker;  // the decoding pass (lcm_field_decoder.cpp)

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

}  // namespace imunoise::io
