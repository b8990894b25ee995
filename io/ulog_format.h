/// @file
/// @brief The message formats of a PX4 ULog file (internal to io/ulog_reader): the text of a
/// format message ('F', "name:type field;type field;…") parsed into fields with their byte
/// offsets, nested formats resolved, and the fields of a data message read by name.
///
/// Field types (docs.px4.io "ULog File Format", "Format Message"): int8_t … uint64_t, float,
/// double, bool, char, a nested format's name, each optionally a fixed array "type[n]"; fields
/// are packed (no alignment: PX4 inserts explicit "_padding" fields), and a data message may
/// omit the padding at its end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::io {

/// One field of a format.
struct UlogField {
  std::string type;         ///< the element type: "float", "uint64_t", a nested format name
  std::string name;         ///< "gyro_rad", "_padding0"
  std::size_t count = 1;    ///< array length (1: not an array)
  std::size_t offset = 0;   ///< from the start of the data (after the msg_id)
  std::size_t element = 0;  ///< bytes per element
};

/// One message format.
struct UlogFormat {
  std::string name;
  std::vector<UlogField> fields;
  std::size_t size = 0;  ///< bytes of the whole struct, padding included
};

/// The formats of a file, as they arrive.
class UlogFormats {
 public:
  /// Adds the format of the text TEXT ("name:type field;…"); an error text when it does not
  /// parse or its name has a format already (empty when it is added). Nested types are
  /// resolved on use (resolve()); the formats resolve() returns stay valid while this lives.
  std::string add(std::string_view text);

  /// Lays out format NAME (its nested formats recursively); nullptr with ERROR when a type is
  /// unknown, nested too deep or the struct is too large.
  const UlogFormat* resolve(const std::string& name, std::string& error);

 private:
  std::map<std::string, std::string> texts_;  // name → the fields' text
  std::map<std::string, UlogFormat> resolved_;
  std::size_t size_of(const std::string& type, int depth, std::string& error);
};

/// The size of a basic ULog type in bytes, or 0 for a name that is not one.
std::size_t ulog_basic_type_size(std::string_view type);

/// Finds FIELD in FORMAT with element type TYPE and array length COUNT; an error text when it
/// is missing or of another type.
const UlogField* find_ulog_field(const UlogFormat& format, std::string_view field,
                                 std::string_view type, std::size_t count, std::string& error);

/// Reads element I of FIELD from DATA as a double (float, double, integers); false when DATA
/// is too short for it.
bool read_ulog_number(std::span<const std::uint8_t> data, const UlogField& field, std::size_t i,
                      double& value);
/// Reads an unsigned 64-bit FIELD (element 0); false when DATA is too short.
bool read_ulog_u64(std::span<const std::uint8_t> data, const UlogField& field,
                   std::uint64_t& value);

}  // namespace imunoise::io
