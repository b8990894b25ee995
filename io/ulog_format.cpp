/// @file
/// @brief ULog message formats (see ulog_format.h).
#include "io/ulog_format.h"

#include <bit>
#include <charconv>
#include <cstring>

#include "io/binary_file.h"

namespace imunoise::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "read_ulog_number copies ULog's little-endian floats as they are");

constexpr int kMaxNesting = 8;
constexpr std::size_t kMaxStructBytes = 65535;  // a ULog message holds at most 65535 bytes

struct BasicType {
  std::string_view name;
  std::size_t size;
};
constexpr BasicType kBasicTypes[] = {
    {"int8_t", 1},  {"uint8_t", 1},  {"int16_t", 2}, {"uint16_t", 2},
    {"int32_t", 4}, {"uint32_t", 4}, {"int64_t", 8}, {"uint64_t", 8},
    {"float", 4},   {"double", 8},   {"bool", 1},    {"char", 1},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\n' || s.front() == '\r')) {
    s.remove_prefix(1);
  }
  while (!s.empty() &&
         (s.back() == ' ' || s.back() == '\n' || s.back() == '\r' || s.back() == '\0')) {
    s.remove_suffix(1);
  }
  return s;
}

/// "float[3] gyro_rad" → type "float", count 3, name "gyro_rad".
std::string parse_field(std::string_view text, UlogField& field) {
  text = trim(text);
  const std::size_t space = text.find(' ');
  if (space == std::string_view::npos) return "field " + quoted_bytes(text) + " has no name";
  std::string_view type = text.substr(0, space);
  field.name = std::string(trim(text.substr(space + 1)));
  field.count = 1;
  if (const std::size_t open = type.find('['); open != std::string_view::npos) {
    if (type.back() != ']') return "field type " + quoted_bytes(type) + " has no closing ']'";
    const std::string_view digits = type.substr(open + 1, type.size() - open - 2);
    std::size_t n = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec != std::errc() || end != digits.data() + digits.size() || n == 0 ||
        n > kMaxStructBytes) {
      return "field type " + quoted_bytes(type) + " has a bad array length";
    }
    field.count = n;
    type = type.substr(0, open);
  }
  if (type.empty() || field.name.empty()) return "field " + quoted_bytes(text) + " is incomplete";
  field.type = std::string(type);
  return {};
}

}  // namespace

std::size_t ulog_basic_type_size(std::string_view type) {
  for (const BasicType& t : kBasicTypes) {
    if (t.name == type) return t.size;
  }
  return 0;
}

std::string UlogFormats::add(std::string_view text) {
  text = trim(text);
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0) {
    return "format " + quoted_bytes(text) + " has no \"name:\"";
  }
  const std::string name(text.substr(0, colon));
  // Once laid out, a format's fields are pointed to (readers keep them): a second definition
  // is refused rather than replacing them.
  if (!texts_.emplace(name, std::string(text.substr(colon + 1))).second) {
    return "format " + quoted_bytes(name) + " is defined twice";
  }
  return {};
}

std::size_t UlogFormats::size_of(const std::string& type, int depth, std::string& error) {
  if (const std::size_t basic = ulog_basic_type_size(type); basic > 0) return basic;
  if (const auto done = resolved_.find(type); done != resolved_.end()) return done->second.size;
  if (depth > kMaxNesting) {
    error = "formats nested deeper than " + std::to_string(kMaxNesting) + " (a cycle?) at " +
            quoted_bytes(type);
    return 0;
  }
  const auto it = texts_.find(type);
  if (it == texts_.end()) {
    error = "unknown field type " + quoted_bytes(type);
    return 0;
  }
  UlogFormat format;
  format.name = type;
  std::string_view rest = it->second;
  while (!trim(rest).empty()) {
    const std::size_t semi = rest.find(';');
    const std::string_view item = rest.substr(0, semi);
    rest = semi == std::string_view::npos ? std::string_view() : rest.substr(semi + 1);
    if (trim(item).empty()) continue;
    UlogField field;
    if (const std::string e = parse_field(item, field); !e.empty()) {
      error = "format " + quoted_bytes(type) + ": " + e;
      return 0;
    }
    field.element = size_of(field.type, depth + 1, error);
    if (field.element == 0) return 0;
    field.offset = format.size;
    format.size += field.element * field.count;
    if (format.size > kMaxStructBytes) {
      error = "format " + quoted_bytes(type) + " is larger than a ULog message can be";
      return 0;
    }
    format.fields.push_back(std::move(field));
  }
  const std::size_t size = format.size;
  resolved_[type] = std::move(format);
  return size;
}

const UlogFormat* UlogFormats::resolve(const std::string& name, std::string& error) {
  if (const auto it = resolved_.find(name); it != resolved_.end()) return &it->second;
  error.clear();
  (void)size_of(name, 0, error);
  if (!error.empty()) return nullptr;
  const auto it = resolved_.find(name);
  if (it == resolved_.end()) {
    error = "no format " + quoted_bytes(name);
    return nullptr;
  }
  return &it->second;
}

const UlogField* find_ulog_field(const UlogFormat& format, std::string_view field,
                                 std::string_view type, std::size_t count, std::string& error) {
  for (const UlogField& f : format.fields) {
    if (f.name != field) continue;
    if (f.type != type || (count > 0 && f.count != count) || (count == 0 && f.count < 1)) {
      // Built with append() only: GCC 12 raises a false -Wrestrict on "[" + std::to_string(…).
      const auto array = [](std::size_t n) {
        std::string out;
        if (n > 1) out.append("[").append(std::to_string(n)).append("]");
        return out;
      };
      error = "field " + quoted_bytes(format.name + "." + f.name) + " is ";
      error.append(f.type).append(array(f.count)).append(", expected ");
      error.append(type).append(array(count));
      return nullptr;
    }
    return &f;
  }
  error = "format " + quoted_bytes(format.name) + " has no field " + quoted_bytes(field);
  return nullptr;
}

bool read_ulog_number(std::span<const std::uint8_t> data, const UlogField& field, std::size_t i,
                      double& value) {
  const std::size_t at = field.offset + i * field.element;
  if (i >= field.count || at + field.element > data.size()) return false;
  const std::uint8_t* p = data.data() + at;
  const std::string& t = field.type;
  if (t == "float") {
    float f = 0;
    std::memcpy(&f, p, 4);  // ULog is little endian, as every platform this builds on
    value = f;
  } else if (t == "double") {
    std::memcpy(&value, p, 8);
  } else if (t == "int16_t") {
    value = static_cast<std::int16_t>(load_le16(p));
  } else if (t == "uint8_t") {
    value = *p;
  } else if (t == "int32_t") {
    value = static_cast<std::int32_t>(load_le32(p));
  } else if (t == "uint32_t") {
    value = load_le32(p);
  } else {
    return false;
  }
  return true;
}

bool read_ulog_u64(std::span<const std::uint8_t> data, const UlogField& field,
                   std::uint64_t& value) {
  if (field.offset + 8 > data.size()) return false;
  value = load_le64(data.data() + field.offset);
  return true;
}

}  // namespace imunoise::io
