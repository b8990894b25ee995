/// @file
/// @brief The generic decoder of LCM messages (see lcm_field_decoder.h): field selection by
/// path, then one bounds-checked pass over each encoded message.
#include "io/lcm_field_decoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_type_definition_internal.h"

namespace imunoise::io {
namespace {

using detail::is_identifier;
using detail::is_size_type;
using detail::kMaxDimensions;
using detail::kMaxNestingDepth;
using detail::primitive_info;

// A fixed-size array named whole in add_field ("gyro" for double gyro[3]) gets one slot per
// element; real selections are 3-vectors, the bound keeps a hostile dimension from
// allocating billions of slots.
constexpr std::int64_t kMaxWholeArrayElements = 4096;
constexpr std::uint64_t kFingerprintBytes = 8;

// ---------------------------------------------------------------------------------------------
// Field paths: "a.b[1].c[0][2]"

struct PathSegment {
  std::string name;
  std::vector<std::int64_t> indices;
};

std::vector<PathSegment> parse_field_path(const std::string& path, const std::string& file) {
  const auto bad = [&](const std::string& why) {
    return InputError(located_message(file, 0, 0, "bad field path '" + path + "': " + why));
  };
  std::vector<PathSegment> segments;
  std::string_view rest = path;
  while (true) {
    PathSegment segment;
    std::size_t n = 0;
    while (n < rest.size() && rest[n] != '.' && rest[n] != '[') ++n;
    if (!is_identifier(rest.substr(0, n))) throw bad("expected a member name");
    segment.name = std::string(rest.substr(0, n));
    rest.remove_prefix(n);
    while (!rest.empty() && rest.front() == '[') {
      const auto close = rest.find(']');
      if (close == std::string_view::npos) throw bad("missing ']'");
      const std::string_view digits = rest.substr(1, close - 1);
      std::int64_t index = 0;
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() ||
          index < 0) {
        throw bad("index '" + std::string(digits) + "' is not a non-negative integer");
      }
      segment.indices.push_back(index);
      rest.remove_prefix(close + 1);
    }
    segments.push_back(std::move(segment));
    if (rest.empty()) return segments;
    if (rest.front() != '.') throw bad("unexpected '" + std::string(1, rest.front()) + "'");
    rest.remove_prefix(1);
  }
}

std::string index_text(const std::vector<std::int64_t>& indices) {
  std::string out;
  for (const std::int64_t i : indices) out.append("[").append(std::to_string(i)).append("]");
  return out;
}

/// "utime, gyro[3], tau[n_tau], pose (pose_t)": a struct's members for messages.
std::string member_list(const LcmStructType& s) {
  std::string out;
  for (const LcmMember& m : s.members) {
    if (!out.empty()) out.append(", ");
    out.append(m.name);
    for (const LcmDimension& d : m.dimensions) out.append("[").append(d.size_text).append("]");
    if (!m.primitive) out.append(" (").append(m.type_name).append(")");
  }
  return out.empty() ? "none" : out;
}

/// Minimum encoded size of each struct (0 only for structs that encode to nothing at all:
/// a variable array needs its size member, every primitive takes bytes).
std::vector<std::uint64_t> min_encoded_sizes(const LcmTypeFile& file) {
  std::vector<std::optional<std::uint64_t>> memo(file.structs.size());
  const auto size_of = [&](auto&& self, std::size_t index) -> std::uint64_t {
    if (memo[index]) return *memo[index];
    std::uint64_t total = 0;
    for (const LcmMember& m : file.structs[index].members) {
      std::uint64_t count = 1;
      for (const LcmDimension& d : m.dimensions) {
        // Saturating: [2^20][2^20][2^24] must not wrap to 0 (a struct "of no bytes" is skipped).
        const auto size = static_cast<std::uint64_t>(d.fixed_size);
        count = d.variable ? 0
                : size != 0 && count > (1ull << 40) / size
                    ? 1ull << 40
                    : std::min<std::uint64_t>(count * size, 1ull << 40);
      }
      const std::uint64_t each =
          m.primitive ? primitive_info(*m.primitive).bytes : self(self, m.struct_index);
      total = std::min<std::uint64_t>(total + count * std::min<std::uint64_t>(each, 1ull << 20),
                                      1ull << 62);
    }
    memo[index] = total;
    return total;
  };
  std::vector<std::uint64_t> out;
  for (std::size_t i = 0; i < file.structs.size(); ++i) out.push_back(size_of(size_of, i));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Big-endian loads by shifts (no aliasing, no alignment assumption).

std::uint64_t load_be(const unsigned char* p, std::uint64_t bytes) {
  std::uint64_t v = 0;
  for (std::uint64_t i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

/// One numeric element; its exact integer value in *integer (0 for float and double).
double load_number(LcmPrimitive type, const unsigned char* p, std::int64_t* integer) {
  switch (type) {
    case LcmPrimitive::kInt8:
    case LcmPrimitive::kBoolean:  // LCM's boolean is an int8_t
      *integer = static_cast<std::int8_t>(p[0]);
      break;
    case LcmPrimitive::kByte:
      *integer = p[0];
      break;
    case LcmPrimitive::kInt16:
      *integer = static_cast<std::int16_t>(load_be(p, 2));
      break;
    case LcmPrimitive::kInt32:
      *integer = static_cast<std::int32_t>(load_be(p, 4));
      break;
    case LcmPrimitive::kInt64:
      *integer = static_cast<std::int64_t>(load_be(p, 8));
      break;
    case LcmPrimitive::kFloat:
      *integer = 0;
      return std::bit_cast<float>(static_cast<std::uint32_t>(load_be(p, 4)));
    case LcmPrimitive::kDouble:
      *integer = 0;
      return std::bit_cast<double>(load_be(p, 8));
    case LcmPrimitive::kString:
      *integer = 0;
      return 0.0;
  }
  return static_cast<double>(*integer);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Decoder: field selection

LcmFieldDecoder::LcmFieldDecoder(LcmTypeFile file, std::size_t struct_index)
    : file_(std::move(file)), struct_index_(struct_index) {
  if (struct_index_ >= file_.structs.size()) {
    throw InputError(located_message(file_.path, 0, 0, "struct index out of range"));
  }
  fingerprint_ = lcm_fingerprint(file_, struct_index_);
  min_encoded_bytes_ = min_encoded_sizes(file_);
  nodes_.push_back(SelectionNode{std::vector<MemberSelection>(type().members.size())});
}

std::size_t LcmFieldDecoder::node_for(std::size_t parent_node, std::size_t member,
                                      const std::vector<std::int64_t>& index,
                                      std::size_t struct_index) {
  for (const ElementNode& e : nodes_[parent_node].members[member].elements) {
    if (e.index == index) return e.node;
  }
  const std::size_t node = nodes_.size();
  nodes_.push_back(
      SelectionNode{std::vector<MemberSelection>(file_.structs[struct_index].members.size())});
  nodes_[parent_node].members[member].elements.push_back(ElementNode{index, node});
  return node;
}

std::vector<std::size_t> LcmFieldDecoder::add_field(const std::string& path) {
  const auto fail = [&](const std::string& problem) {
    return InputError(located_message(file_.path, 0, 0, "field '" + path + "': " + problem));
  };
  const std::vector<PathSegment> segments = parse_field_path(path, file_.path);
  std::size_t struct_index = struct_index_;
  std::size_t node = 0;
  std::string prefix;  // canonical path so far
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const PathSegment& seg = segments[k];
    const LcmStructType& s = file_.structs[struct_index];
    const auto it = std::find_if(s.members.begin(), s.members.end(),
                                 [&](const LcmMember& m) { return m.name == seg.name; });
    if (it == s.members.end()) {
      throw fail("struct '" + s.full_name() + "' has no member '" + seg.name +
                 "'; its members: " + member_list(s));
    }
    const LcmMember& m = *it;
    const auto member = static_cast<std::size_t>(it - s.members.begin());
    const bool last = k + 1 == segments.size();
    const bool whole_array = last && seg.indices.empty() && m.dimensions.size() == 1 &&
                             !m.dimensions[0].variable && m.primitive;
    if (seg.indices.size() != m.dimensions.size() && !whole_array) {
      throw fail(
          "'" + m.name + "' has " + std::to_string(m.dimensions.size()) + " dimension(s) but " +
          std::to_string(seg.indices.size()) + " index(es) are given" +
          (m.dimensions.size() == 1 && m.dimensions[0].variable
               ? " (a variable-length array is selected element by element, e.g. " + m.name + "[0])"
               : ""));
    }
    for (std::size_t d = 0; d < seg.indices.size(); ++d) {
      if (!m.dimensions[d].variable && seg.indices[d] >= m.dimensions[d].fixed_size) {
        throw fail("index " + std::to_string(seg.indices[d]) + " is beyond dimension " +
                   std::to_string(d + 1) + " of '" + m.name + "' (size " +
                   m.dimensions[d].size_text + ")");
      }
    }
    prefix.append(prefix.empty() ? "" : ".").append(m.name);
    if (!last) {
      if (m.primitive) throw fail("'" + m.name + "' is of type " + m.type_name + ", not a struct");
      prefix.append(index_text(seg.indices));
      node = node_for(node, member, seg.indices, m.struct_index);
      struct_index = m.struct_index;
      continue;
    }
    if (!m.primitive) {
      throw fail("'" + m.name + "' is a struct (" + m.type_name +
                 "); name one of its members: " + member_list(file_.structs[m.struct_index]));
    }
    if (*m.primitive == LcmPrimitive::kString)
      throw fail("'" + m.name + "' is a string, not a number");
    std::vector<std::vector<std::int64_t>> elements;
    if (whole_array) {
      // One slot (and name) per element is allocated here, before any message is seen: a
      // huge dimension in a hostile definition must not exhaust memory.
      if (m.dimensions[0].fixed_size > kMaxWholeArrayElements) {
        throw fail("'" + m.name + "' has " + m.dimensions[0].size_text +
                   " elements; a whole array selects at most " +
                   std::to_string(kMaxWholeArrayElements) + " (name its elements, e.g. " + m.name +
                   "[0])");
      }
      for (std::int64_t i = 0; i < m.dimensions[0].fixed_size; ++i) elements.push_back({i});
    } else {
      elements.push_back(seg.indices);
    }
    std::vector<std::size_t> slots;
    for (auto& index : elements) {
      const std::size_t slot = slot_paths_.size();
      slot_paths_.push_back(prefix + index_text(index));
      slot_types_.push_back(*m.primitive);
      nodes_[node].members[member].leaves.push_back(ElementPick{std::move(index), slot});
      slots.push_back(slot);
    }
    return slots;
  }
  throw fail("empty path");  // not reached: parse_field_path returns at least one segment
}

// ---------------------------------------------------------------------------------------------
// Decoder: the pass over one message

/// Walks one encoded message in order, checking every length against the bytes left, and
/// stores the selected elements (slots) and/or every leaf with its name (all).
class LcmFieldDecoder::Walker {
 public:
  Walker(LcmFieldDecoder& decoder, std::span<const unsigned char> bytes, LcmSlotValues* slots,
         std::vector<LcmFieldValue>* all, std::string& error)
      : d_(decoder), bytes_(bytes), slots_(slots), all_(all), error_(error) {}

  bool run() {
    d_.scratch_.clear();
    if (bytes_.size() < kFingerprintBytes) {
      return fail("a " + std::to_string(bytes_.size()) +
                  "-byte message is shorter than its 8-byte fingerprint");
    }
    const std::uint64_t fingerprint = load_be(bytes_.data(), kFingerprintBytes);
    if (fingerprint != d_.fingerprint_) {
      return fail("fingerprint " + lcm_fingerprint_text(fingerprint) +
                  " is not the fingerprint of " + d_.type().full_name() + " (" +
                  lcm_fingerprint_text(d_.fingerprint_) + ")");
    }
    pos_ = kFingerprintBytes;
    if (!walk_struct(d_.struct_index_, slots_ ? &d_.nodes_[0] : nullptr, 0)) return false;
    if (pos_ != bytes_.size()) {
      return fail(std::to_string(bytes_.size() - pos_) + " bytes left over after the " +
                  d_.type().full_name() + " message: the definition does not match the sender's");
    }
    return true;
  }

 private:
  bool fail(const std::string& problem) {
    error_ = "byte " + std::to_string(pos_) + ": " + problem;
    return false;
  }
  std::uint64_t remaining() const { return bytes_.size() - pos_; }

  bool walk_struct(std::size_t index, const SelectionNode* selection, int depth) {
    const LcmStructType& s = d_.file_.structs[index];
    // The integer scalars of this instance, for the variable dimensions of later members.
    const std::size_t base = d_.scratch_.size();
    d_.scratch_.resize(base + s.members.size(), 0);
    for (std::size_t i = 0; i < s.members.size(); ++i) {
      const MemberSelection* member_selection = selection ? &selection->members[i] : nullptr;
      if (!walk_member(s.members[i], base, i, member_selection, depth)) return false;
    }
    d_.scratch_.resize(base);
    return true;
  }

  /// The dimensions of `m` in this message and their product.
  bool dimensions(const LcmMember& m, std::size_t base,
                  std::array<std::int64_t, kMaxDimensions>& dims, std::uint64_t* count) {
    *count = 1;
    for (std::size_t k = 0; k < m.dimensions.size(); ++k) {
      const LcmDimension& dim = m.dimensions[k];
      const std::int64_t size = dim.variable ? d_.scratch_[base + dim.size_member] : dim.fixed_size;
      if (size < 0) {
        return fail("size " + dim.size_text + " = " + std::to_string(size) + " of '" + m.name +
                    "' is negative");
      }
      dims[k] = size;
      // Any count beyond the message length fails below; saturating keeps it from wrapping.
      *count = (size != 0 && *count > (1ull << 62) / static_cast<std::uint64_t>(size))
                   ? (1ull << 62)
                   : *count * static_cast<std::uint64_t>(size);
    }
    return true;
  }

  /// Row-major flat index of `index` within `dims`; nullopt when beyond them.
  static std::optional<std::uint64_t> flat_index(
      const std::vector<std::int64_t>& index,
      const std::array<std::int64_t, kMaxDimensions>& dims) {
    std::uint64_t flat = 0;
    for (std::size_t k = 0; k < index.size(); ++k) {
      if (index[k] >= dims[k]) return std::nullopt;
      flat = flat * static_cast<std::uint64_t>(dims[k]) + static_cast<std::uint64_t>(index[k]);
    }
    return flat;
  }
  bool fail_not_present(const std::string& what, const LcmMember& m,
                        const std::array<std::int64_t, kMaxDimensions>& dims) {
    std::string sizes;
    for (std::size_t k = 0; k < m.dimensions.size(); ++k) {
      sizes.append("[").append(std::to_string(dims[k])).append("]");
    }
    return fail("'" + what + "' is not in this message: '" + m.name + "' is " + sizes + " here");
  }

  /// "name[i][j]" of element `flat`.
  std::string element_name(const LcmMember& m, std::uint64_t flat,
                           const std::array<std::int64_t, kMaxDimensions>& dims) const {
    std::array<std::uint64_t, kMaxDimensions> index{};
    for (std::size_t k = m.dimensions.size(); k-- > 0;) {
      index[k] = flat % static_cast<std::uint64_t>(dims[k]);
      flat /= static_cast<std::uint64_t>(dims[k]);
    }
    std::string out = prefix_ + m.name;
    for (std::size_t k = 0; k < m.dimensions.size(); ++k) {
      out.append("[").append(std::to_string(index[k])).append("]");
    }
    return out;
  }

  bool walk_member(const LcmMember& m, std::size_t base, std::size_t member_index,
                   const MemberSelection* selection, int depth) {
    std::array<std::int64_t, kMaxDimensions> dims{};
    std::uint64_t count = 0;
    if (!dimensions(m, base, dims, &count)) return false;
    if (!m.primitive) return walk_structs(m, dims, count, selection, depth);
    if (*m.primitive == LcmPrimitive::kString) return walk_strings(m, dims, count);
    const std::uint64_t each = primitive_info(*m.primitive).bytes;
    if (count > remaining() / each) {
      return fail("'" + m.name + "' needs " + std::to_string(count) + " × " + std::to_string(each) +
                  " bytes, the message has " + std::to_string(remaining()) + " left");
    }
    const unsigned char* start = bytes_.data() + pos_;
    std::int64_t integer = 0;
    if (m.dimensions.empty() && is_size_type(*m.primitive)) {
      load_number(*m.primitive, start, &integer);
      d_.scratch_[base + member_index] = integer;  // may be the size of a later array
    }
    if (selection) {
      for (const ElementPick& pick : selection->leaves) {
        const auto flat = flat_index(pick.index, dims);
        if (!flat) return fail_not_present(d_.slot_paths_[pick.slot], m, dims);
        slots_->values[pick.slot] = load_number(*m.primitive, start + *flat * each, &integer);
        slots_->integers[pick.slot] = integer;
      }
    }
    if (all_) {
      for (std::uint64_t e = 0; e < count; ++e) {
        LcmFieldValue v;
        v.path = m.dimensions.empty() ? prefix_ + m.name : element_name(m, e, dims);
        v.type = *m.primitive;
        v.value = load_number(*m.primitive, start + e * each, &v.integer);
        all_->push_back(std::move(v));
      }
    }
    pos_ += count * each;
    return true;
  }

  bool walk_strings(const LcmMember& m, const std::array<std::int64_t, kMaxDimensions>& dims,
                    std::uint64_t count) {
    if (count > remaining() / primitive_info(LcmPrimitive::kString).bytes) {
      return fail("'" + m.name + "' holds " + std::to_string(count) +
                  " strings, more than the bytes left allow");
    }
    for (std::uint64_t e = 0; e < count; ++e) {
      if (remaining() < 4)
        return fail("the message ends inside the length of string '" + m.name + "'");
      const auto length = static_cast<std::int32_t>(load_be(bytes_.data() + pos_, 4));
      pos_ += 4;
      // LCM writes strlen + 1 (the NUL is sent); 0 or less is never written.
      if (length < 1 || static_cast<std::uint64_t>(length) > remaining()) {
        return fail("string '" + m.name + "' has length " + std::to_string(length) + " with " +
                    std::to_string(remaining()) + " bytes left");
      }
      if (all_) {
        LcmFieldValue v;
        v.path = m.dimensions.empty() ? prefix_ + m.name : element_name(m, e, dims);
        v.type = LcmPrimitive::kString;
        v.text.assign(reinterpret_cast<const char*>(bytes_.data() + pos_),
                      static_cast<std::size_t>(length - 1));
        all_->push_back(std::move(v));
      }
      pos_ += static_cast<std::uint64_t>(length);
    }
    return true;
  }

  bool walk_structs(const LcmMember& m, const std::array<std::int64_t, kMaxDimensions>& dims,
                    std::uint64_t count, const MemberSelection* selection, int depth) {
    const std::uint64_t min_bytes = d_.min_encoded_bytes_[m.struct_index];
    // A struct of minimum size 0 encodes to nothing and has no leaves: nothing to walk.
    if (min_bytes == 0) return true;
    if (count > remaining() / min_bytes) {
      return fail("'" + m.name + "' holds " + std::to_string(count) + " structs of at least " +
                  std::to_string(min_bytes) + " bytes, more than the bytes left allow");
    }
    if (depth >= kMaxNestingDepth) return fail("structs nested too deep");  // refused at parse
    const std::vector<ElementNode>* picked = selection ? &selection->elements : nullptr;
    if (picked) {
      for (const ElementNode& p : *picked) {
        if (!flat_index(p.index, dims))
          return fail_not_present(m.name + index_text(p.index), m, dims);
      }
    }
    const std::size_t prefix_length = prefix_.size();
    for (std::uint64_t e = 0; e < count; ++e) {
      const SelectionNode* child = nullptr;
      if (picked) {
        for (const ElementNode& p : *picked) {
          if (flat_index(p.index, dims) == e) child = &d_.nodes_[p.node];
        }
      }
      if (all_) {
        prefix_ = (m.dimensions.empty() ? prefix_ + m.name : element_name(m, e, dims)) + ".";
      }
      if (!walk_struct(m.struct_index, child, depth + 1)) return false;
      prefix_.resize(prefix_length);
    }
    return true;
  }

  LcmFieldDecoder& d_;
  std::span<const unsigned char> bytes_;
  LcmSlotValues* slots_;
  std::vector<LcmFieldValue>* all_;
  std::string& error_;
  std::uint64_t pos_ = 0;
  std::string prefix_;  // "outer[1].inner." while walking nested structs (all_ only)
};

bool LcmFieldDecoder::decode(std::span<const unsigned char> message, LcmSlotValues& out,
                             std::string& error) {
  out.values.assign(slot_count(), 0.0);
  out.integers.assign(slot_count(), 0);
  return Walker(*this, message, &out, nullptr, error).run();
}

bool LcmFieldDecoder::decode_all(std::span<const unsigned char> message,
                                 std::vector<LcmFieldValue>& out, std::string& error) {
  out.clear();
  return Walker(*this, message, nullptr, &out, error).run();
}
}  // namespace imunoise::io
