/// @file
/// @brief LCM type definitions at run time: parser, fingerprint, generic decoder, and the
/// mapping of a user's IMU message (see lcm_type_definition.h).
#include "io/lcm_type_definition.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/lcm_log.h"  // lcm_fingerprint_text

namespace imunoise::io {
namespace {

constexpr std::size_t kMaxDefinitionBytes = std::size_t{1} << 20;
// Far beyond any real message type; the bounds keep the decoder's recursion and its
// per-member dimension array small.
constexpr std::size_t kMaxDimensions = 16;
constexpr int kMaxNestingDepth = 32;
// A fixed-size array named whole in add_field ("gyro" for double gyro[3]) gets one slot per
// element; real selections are 3-vectors, the bound keeps a hostile dimension from
// allocating billions of slots.
constexpr std::int64_t kMaxWholeArrayElements = 4096;
constexpr std::uint64_t kFingerprintBytes = 8;

// ---------------------------------------------------------------------------------------------
// Primitive types

struct PrimitiveInfo {
  const char* name;
  LcmPrimitive type;
  std::uint64_t bytes;  // encoded size; strings: the minimum (int32 length + NUL)
};
constexpr std::array<PrimitiveInfo, 9> kPrimitives{{
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

const PrimitiveInfo& info(LcmPrimitive type) { return kPrimitives[static_cast<std::size_t>(type)]; }

std::optional<LcmPrimitive> primitive_named(std::string_view name) {
  for (const PrimitiveInfo& p : kPrimitives) {
    if (name == p.name) return p.type;
  }
  return std::nullopt;
}

/// The types an array size may have (lcm-gen refuses byte and boolean).
bool is_size_type(LcmPrimitive t) {
  return t == LcmPrimitive::kInt8 || t == LcmPrimitive::kInt16 || t == LcmPrimitive::kInt32 ||
         t == LcmPrimitive::kInt64;
}

bool is_integer_valued(LcmPrimitive t) {
  return t != LcmPrimitive::kFloat && t != LcmPrimitive::kDouble && t != LcmPrimitive::kString;
}

// ---------------------------------------------------------------------------------------------
// Text helpers

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  const auto alpha = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  if (!alpha(s.front())) return false;
  return std::all_of(s.begin(), s.end(),
                     [&](char c) { return alpha(c) || (c >= '0' && c <= '9'); });
}

/// "a", "a.b", "pkg.sub.name": identifiers joined by dots.
bool is_dotted_identifier(std::string_view s) {
  while (true) {
    const auto dot = s.find('.');
    if (!is_identifier(s.substr(0, dot))) return false;
    if (dot == std::string_view::npos) return true;
    s.remove_prefix(dot + 1);
  }
}

/// One character for a message: printable ASCII quoted, anything else as \xNN.
std::string char_text(unsigned char c) {
  static constexpr char kDigits[] = "0123456789abcdef";
  if (c >= 0x20 && c < 0x7F) return std::string("'") + static_cast<char>(c) + "'";
  std::string out = "byte \\x";
  out.push_back(kDigits[c >> 4]);
  out.push_back(kDigits[c & 0xFu]);
  return out;
}

/// A C integer literal without sign (decimal, 0x hex, 0 octal), as lcm-gen's C++ output
/// reads an array size. nullopt when not one or beyond INT64_MAX.
std::optional<std::int64_t> parse_c_integer(std::string_view s) {
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  } else if (s.size() > 1 && s[0] == '0') {
    base = 8;
    s.remove_prefix(1);
  }
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value, base);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return value;
}

bool is_number_literal(std::string_view s, bool integer) {
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) s.remove_prefix(1);
  if (s.empty()) return false;
  if (integer) return parse_c_integer(s).has_value();
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

// ---------------------------------------------------------------------------------------------
// Lexer

struct Token {
  enum class Kind { kWord, kPunct, kEnd };
  Kind kind = Kind::kEnd;
  std::string_view text;
  int line = 1;
  int column = 1;
  int end_line = 1;  // just after the token (for "expected ';'" at the end of a line)
  int end_column = 1;
};

class Lexer {
 public:
  Lexer(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  Token next() {
    skip_space_and_comments();
    Token t;
    t.line = line_;
    t.column = column_;
    const std::size_t start = pos_;
    if (pos_ == text_.size()) {
      t.kind = Token::Kind::kEnd;
    } else if (is_punct(text_[pos_])) {
      t.kind = Token::Kind::kPunct;
      advance();
    } else if (is_word_char(text_[pos_])) {
      t.kind = Token::Kind::kWord;
      while (pos_ < text_.size() && is_word_char(text_[pos_])) advance();
    } else {
      fail(line_, column_,
           "unexpected character " + char_text(static_cast<unsigned char>(text_[pos_])));
    }
    t.text = text_.substr(start, pos_ - start);
    t.end_line = line_;
    t.end_column = column_;
    return t;
  }

  [[noreturn]] void fail(int line, int column, const std::string& problem) const {
    throw InputError(located_message(path_, line, column, problem));
  }

 private:
  static bool is_punct(char c) {
    return c == '{' || c == '}' || c == '[' || c == ']' || c == ';' || c == ',' || c == '=';
  }
  // Identifiers, dotted names and number literals (with signs and exponents) are all words;
  // the parser checks which kind each word must be.
  static bool is_word_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '+' || c == '-';
  }

  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

  bool at(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }

  void skip_space_and_comments() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
        advance();
      } else if (at("//")) {
        while (pos_ < text_.size() && text_[pos_] != '\n') advance();
      } else if (at("/*")) {
        const int line = line_, column = column_;
        advance();
        advance();
        while (pos_ < text_.size() && !at("*/")) advance();
        if (pos_ == text_.size()) fail(line, column, "unterminated /* comment");
        advance();
        advance();
      } else {
        return;
      }
    }
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

// ---------------------------------------------------------------------------------------------
// Parser

class Parser {
 public:
  Parser(std::string_view text, const std::string& path) : lexer_(text, path) {
    file_.path = path;
    advance();
  }

  LcmTypeFile parse() {
    while (token_.kind != Token::Kind::kEnd) {
      if (at_word("package")) {
        parse_package();
      } else if (at_word("struct")) {
        parse_struct();
      } else {
        fail_at(token_, "expected 'package' or 'struct', found " + found_text());
      }
    }
    if (file_.structs.empty()) {
      throw InputError(located_message(file_.path, 0, 0, "no struct defined in the file"));
    }
    resolve_nested_types();
    check_nesting();
    return std::move(file_);
  }

 private:
  void advance() {
    previous_ = token_;
    token_ = lexer_.next();
  }
  bool at_word(std::string_view w) const {
    return token_.kind == Token::Kind::kWord && token_.text == w;
  }
  bool at_punct(char c) const {
    return token_.kind == Token::Kind::kPunct && token_.text.front() == c;
  }
  std::string found_text() const {
    if (token_.kind == Token::Kind::kEnd) return "the end of the file";
    constexpr std::size_t kShown = 40;  // a corrupt file may hold one enormous word
    return "'" + std::string(token_.text.substr(0, kShown)) +
           (token_.text.size() > kShown ? "…'" : "'");
  }
  [[noreturn]] void fail_at(const Token& t, const std::string& problem) const {
    lexer_.fail(t.line, t.column, problem);
  }
  /// A missing token is reported just after the previous one (where it belongs).
  [[noreturn]] void fail_missing(const std::string& problem) const {
    lexer_.fail(previous_.end_line, previous_.end_column, problem + ", found " + found_text());
  }
  void expect_punct(char c, const std::string& where) {
    if (!at_punct(c)) fail_missing(std::string("expected '") + c + "' " + where);
    advance();
  }
  /// The current word, checked with `valid`; `what` names it in the error.
  Token take_word(bool (*valid)(std::string_view), const std::string& what) {
    if (token_.kind != Token::Kind::kWord) fail_missing("expected " + what);
    if (!valid(token_.text))
      fail_at(token_, "invalid " + what + " '" + std::string(token_.text) + "'");
    const Token t = token_;
    advance();
    return t;
  }

  void parse_package() {
    advance();
    package_ = std::string(take_word(is_dotted_identifier, "package name").text);
    expect_punct(';', "after the package name");
  }

  void parse_struct() {
    const Token keyword = token_;
    advance();
    const Token name_token = take_word(is_dotted_identifier, "struct name");
    LcmStructType s;
    s.line = keyword.line;
    const std::string_view name = name_token.text;
    const auto dot = name.rfind('.');
    s.package = dot == std::string_view::npos ? package_ : std::string(name.substr(0, dot));
    s.name = std::string(dot == std::string_view::npos ? name : name.substr(dot + 1));
    for (const LcmStructType& other : file_.structs) {
      if (other.full_name() == s.full_name()) {
        fail_at(name_token, "struct '" + s.full_name() + "' is defined twice (first on line " +
                                std::to_string(other.line) + ")");
      }
    }
    expect_punct('{', "after the struct name");
    while (!at_punct('}')) {
      if (token_.kind == Token::Kind::kEnd) {
        fail_at(keyword, "struct '" + s.name + "' has no closing '}'");
      }
      if (at_word("const")) {
        parse_const();
      } else if (at_word("enum")) {
        fail_at(token_, "enums are not supported");
      } else {
        parse_member_declaration(s);
      }
    }
    advance();
    file_.structs.push_back(std::move(s));
  }

  /// `const TYPE NAME = VALUE[, NAME = VALUE];`: checked, then dropped (constants do not
  /// enter the fingerprint or the encoding).
  void parse_const() {
    advance();
    const Token type = take_word(is_identifier, "constant type");
    const auto primitive = primitive_named(type.text);
    if (!primitive || *primitive == LcmPrimitive::kString || *primitive == LcmPrimitive::kByte ||
        *primitive == LcmPrimitive::kBoolean) {
      fail_at(type, "invalid type for a constant: '" + std::string(type.text) +
                        "' (int8_t, int16_t, int32_t, int64_t, float or double)");
    }
    const bool integer = is_size_type(*primitive);
    while (true) {
      take_word(is_identifier, "constant name");
      expect_punct('=', "after the constant name");
      if (token_.kind != Token::Kind::kWord || !is_number_literal(token_.text, integer)) {
        fail_at(token_, std::string("expected ") + (integer ? "an integer" : "a number") +
                            " value, found " + found_text());
      }
      advance();
      if (at_punct(',')) {
        advance();
        continue;
      }
      expect_punct(';', "after the constant");
      return;
    }
  }

  /// `TYPE name[DIM]…, name2…;`
  void parse_member_declaration(LcmStructType& s) {
    const Token type = take_word(is_dotted_identifier, "type name");
    while (true) {
      const Token name = take_word(is_identifier, "member name");
      for (const LcmMember& m : s.members) {
        if (m.name == name.text) {
          fail_at(name, "member '" + m.name + "' is declared twice in struct '" + s.name + "'");
        }
      }
      LcmMember m;
      m.name = std::string(name.text);
      m.type_name = std::string(type.text);
      m.primitive = primitive_named(type.text);
      m.line = type.line;
      m.column = type.column;
      while (at_punct('[')) {
        advance();
        if (m.dimensions.size() == kMaxDimensions) {
          fail_at(token_, "more than " + std::to_string(kMaxDimensions) + " array dimensions");
        }
        m.dimensions.push_back(parse_dimension(s));
        expect_punct(']', "after the array size");
      }
      s.members.push_back(std::move(m));
      if (at_punct(',')) {
        advance();
        continue;
      }
      expect_punct(';', "after member '" + std::string(name.text) + "'");
      return;
    }
  }

  LcmDimension parse_dimension(const LcmStructType& s) {
    if (token_.kind != Token::Kind::kWord) fail_missing("expected an array size");
    const Token t = token_;
    advance();
    LcmDimension d;
    d.size_text = std::string(t.text);
    const char first = t.text.front();
    if (first >= '0' && first <= '9') {
      const auto value = parse_c_integer(t.text);
      if (!value) fail_at(t, "invalid array size '" + d.size_text + "'");
      if (*value <= 0 || *value > INT32_MAX) {
        fail_at(t, "array size " + d.size_text + " is outside 1 … 2147483647");
      }
      d.fixed_size = *value;
      return d;
    }
    if (!is_identifier(t.text)) fail_at(t, "invalid array size '" + d.size_text + "'");
    d.variable = true;
    const auto it = std::find_if(s.members.begin(), s.members.end(),
                                 [&](const LcmMember& m) { return m.name == t.text; });
    if (it == s.members.end()) {
      fail_at(t, "array size '" + d.size_text + "' is not an earlier member of struct '" + s.name +
                     "' (a size member must be declared before the array)");
    }
    if (!it->primitive || !is_size_type(*it->primitive) || !it->dimensions.empty()) {
      fail_at(t, "array size '" + d.size_text + "' must be a scalar int8_t, int16_t, int32_t or " +
                     "int64_t member; it is " + it->type_name +
                     (it->dimensions.empty() ? "" : " (an array)"));
    }
    d.size_member = static_cast<std::size_t>(it - s.members.begin());
    return d;
  }

  /// Members whose type is not primitive name a struct of this file: "name" in the member's
  /// own package, or "package.name".
  void resolve_nested_types() {
    for (LcmStructType& s : file_.structs) {
      for (LcmMember& m : s.members) {
        if (m.primitive) continue;
        const bool qualified = m.type_name.find('.') != std::string::npos;
        const auto it = std::find_if(
            file_.structs.begin(), file_.structs.end(), [&](const LcmStructType& candidate) {
              return qualified ? candidate.full_name() == m.type_name
                               : candidate.name == m.type_name && candidate.package == s.package;
            });
        if (it == file_.structs.end()) {
          lexer_.fail(m.line, m.column,
                      "unknown type '" + m.type_name + "' of member '" + m.name +
                          "': not a primitive type (int8_t, int16_t, int32_t, int64_t, byte, "
                          "float, double, string, boolean) nor a struct defined in this file "
                          "(types from other files are not supported)");
        }
        m.struct_index = static_cast<std::size_t>(it - file_.structs.begin());
      }
    }
  }

  /// Recursive structs cannot be decoded with a bounded stack (and lcm-gen's own code for
  /// them never ends); deep nesting is refused for the same reason.
  void check_nesting() {
    std::vector<int> state(file_.structs.size(), 0);  // 0 new, 1 on the path, 2 done
    std::vector<int> height(file_.structs.size(), 0);
    for (std::size_t i = 0; i < file_.structs.size(); ++i) visit(i, 1, state, height);
  }
  /// The nesting height of struct `index` (1: no struct members).
  int visit(std::size_t index, int depth, std::vector<int>& state, std::vector<int>& height) {
    if (state[index] == 2) return height[index];
    const LcmStructType& s = file_.structs[index];
    const auto too_deep = [&] {
      return InputError(located_message(
          file_.path, s.line, 0,
          "structs nested more than " + std::to_string(kMaxNestingDepth) + " levels deep"));
    };
    if (depth > kMaxNestingDepth) throw too_deep();
    state[index] = 1;
    int h = 1;
    for (const LcmMember& m : s.members) {
      if (m.primitive) continue;
      if (state[m.struct_index] == 1) {
        lexer_.fail(m.line, m.column,
                    "struct '" + file_.structs[m.struct_index].name +
                        "' contains itself (member '" + s.name + "." + m.name +
                        "'): recursive types are not supported");
      }
      h = std::max(h, 1 + visit(m.struct_index, depth + 1, state, height));
    }
    if (h > kMaxNestingDepth) throw too_deep();
    state[index] = 2;
    height[index] = h;
    return h;
  }

  Lexer lexer_;
  Token token_;
  Token previous_;
  std::string package_;
  LcmTypeFile file_;
};

// ---------------------------------------------------------------------------------------------
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
          m.primitive ? info(*m.primitive).bytes : self(self, m.struct_index);
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
// Public: definitions and fingerprint

std::size_t LcmTypeFile::find_struct(const std::string& type_name) const {
  std::string names;
  for (const LcmStructType& s : structs)
    names.append(names.empty() ? "" : ", ").append(s.full_name());
  if (type_name.empty()) {
    if (structs.size() == 1) return 0;
    throw InputError(located_message(path, 0, 0,
                                     "the file defines " + std::to_string(structs.size()) +
                                         " structs (" + names + "): name the one to use"));
  }
  std::vector<std::size_t> matches;
  for (std::size_t i = 0; i < structs.size(); ++i) {
    if (structs[i].full_name() == type_name) return i;
    if (structs[i].name == type_name) matches.push_back(i);
  }
  if (matches.size() == 1) return matches.front();
  throw InputError(located_message(
      path, 0, 0,
      (matches.empty() ? "no struct '" + type_name + "' in the file"
                       : "struct name '" + type_name + "' is ambiguous: give the package") +
          "; it defines: " + names));
}

LcmTypeFile parse_lcm_type_definition(std::string_view text, const std::string& path) {
  if (text.size() > kMaxDefinitionBytes) {
    throw InputError(located_message(path, 0, 0, "larger than 1 MiB: not a type definition"));
  }
  return Parser(text, path).parse();
}

LcmTypeFile read_lcm_type_definition(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw InputError(located_message(path, 0, 0, "cannot open: no such file"));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(located_message(path, 0, 0, "cannot open: not a regular file"));
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxDefinitionBytes) {
    throw InputError(located_message(path, 0, 0, "larger than 1 MiB: not a type definition"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(located_message(path, 0, 0, "cannot open for reading"));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(located_message(path, 0, 0, "read error"));
  return parse_lcm_type_definition(text, path);
}

std::uint64_t lcm_fingerprint(const LcmTypeFile& file, std::size_t struct_index) {
  std::vector<std::optional<std::uint64_t>> memo(file.structs.size());
  return computed_hash(file, struct_index, memo);
}

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
    const std::uint64_t each = info(*m.primitive).bytes;
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
    if (count > remaining() / info(LcmPrimitive::kString).bytes) {
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

// ---------------------------------------------------------------------------------------------
// A user's IMU type

namespace {

LcmFieldDecoder user_type_decoder(const LcmUserType& user_type) {
  LcmTypeFile file = read_lcm_type_definition(user_type.definition_path);
  const std::size_t index = file.find_struct(user_type.type_name);
  return LcmFieldDecoder(std::move(file), index);
}

/// "rad/s", or "0.017453292519943295 rad/s" for a field in deg/s: the source unit in SI.
std::string unit_text(double scale_to_si, const char* si_unit) {
  if (scale_to_si == 1.0) return si_unit;
  return shortest_number_text(scale_to_si) + " " + si_unit;
}

/// llround semantics (half away from zero) for an integer quotient.
std::int64_t divide_rounded(std::int64_t value, std::int64_t divisor) {
  std::int64_t quotient = value / divisor;
  const std::int64_t remainder = value % divisor;
  if (remainder != 0 && static_cast<std::uint64_t>(remainder < 0 ? -remainder : remainder) * 2 >=
                            static_cast<std::uint64_t>(divisor)) {
    quotient += value < 0 ? -1 : 1;
  }
  return quotient;
}

/// `value` × `us_per_unit` as an integer when that factor is an integer or the inverse of one
/// (ns, ms, s stamps): exact, unlike the double product for stamps beyond 2^53.
std::optional<std::int64_t> exact_integer_stamp_us(std::int64_t value, double us_per_unit,
                                                   bool* overflow) {
  *overflow = false;
  const double multiplier = std::round(us_per_unit);
  if (multiplier >= 1.0 && multiplier < 9e15 &&
      std::abs(us_per_unit - multiplier) <= 1e-9 * multiplier) {
    std::int64_t out = 0;
    *overflow = __builtin_mul_overflow(value, static_cast<std::int64_t>(multiplier), &out);
    return out;
  }
  const double divisor = std::round(1.0 / us_per_unit);
  if (divisor >= 2.0 && divisor < 9e15 && std::abs(1.0 / us_per_unit - divisor) <= 1e-9 * divisor) {
    return divide_rounded(value, static_cast<std::int64_t>(divisor));
  }
  return std::nullopt;
}

}  // namespace

LcmUserImuDecoder::LcmUserImuDecoder(const LcmUserType& user_type)
    : definition_path_(user_type.definition_path),
      decoder_(user_type_decoder(user_type)),
      time_unit_s_(user_type.time_unit_s),
      increments_(user_type.increments) {
  const auto fail = [&](const std::string& problem) {
    return InputError(located_message(definition_path_, 0, 0, problem));
  };
  if (!(std::isfinite(time_unit_s_) && time_unit_s_ > 0.0)) {
    throw fail("time unit " + shortest_number_text(time_unit_s_) + " s is not a positive number");
  }
  const std::vector<std::size_t> time_slots = decoder_.add_field(user_type.time_field);
  if (time_slots.size() != 1) {
    throw fail("time field '" + user_type.time_field + "' must be one number, not an array");
  }
  time_slot_ = time_slots.front();

  const auto add_group = [&](const std::vector<std::string>& fields, double scale,
                             const char* group, std::size_t first) {
    if (!(std::isfinite(scale) && scale != 0.0)) {
      throw fail(std::string(group) + " scale " + shortest_number_text(scale) +
                 " is not a finite non-zero factor");
    }
    if (fields.empty()) {
      throw fail(std::string("no ") + group + " fields given: name one array of 3 or three " +
                 "fields (both gyro and accel fields are needed)");
    }
    std::vector<std::size_t> slots;
    for (const std::string& f : fields) {
      const std::vector<std::size_t> s = decoder_.add_field(f);
      if (fields.size() > 1 && s.size() != 1) {
        throw fail(std::string(group) + " field '" + f + "' is an array; with several " + group +
                   " fields each must be one number");
      }
      slots.insert(slots.end(), s.begin(), s.end());
    }
    if (slots.size() != 3) {
      throw fail(std::string(group) + " fields give " + std::to_string(slots.size()) +
                 " value(s); x, y, z need 3 (one array of 3 or three fields)");
    }
    for (std::size_t a = 0; a < 3; ++a) {
      value_slots_[first + a] = slots[a];
      scale_to_si_[first + a] = scale;
    }
  };
  add_group(user_type.gyro_fields, user_type.gyro_scale_to_si, "gyro", 0);
  add_group(user_type.accel_fields, user_type.accel_scale_to_si, "accel", 3);
}

ImuSampleColumns LcmUserImuDecoder::make_columns() const {
  ImuSampleColumns columns;
  columns.increments = increments_;
  for (std::size_t c = 0; c < 6; ++c) {
    columns.source_fields[c] = decoder_.slot_path(value_slots_[c]);
    const char* si = c < 3 ? (increments_ ? "rad" : "rad/s") : (increments_ ? "m/s" : "m/s^2");
    columns.source_units[c] = unit_text(scale_to_si_[c], si);
  }
  return columns;
}

bool LcmUserImuDecoder::stamp_us(std::int64_t* out, std::string& error) const {
  const double us_per_unit = time_unit_s_ * 1e6;
  const std::string& field = decoder_.slot_path(time_slot_);
  if (is_integer_valued(decoder_.slot_type(time_slot_))) {
    bool overflow = false;
    const auto exact =
        exact_integer_stamp_us(slot_values_.integers[time_slot_], us_per_unit, &overflow);
    if (exact && !overflow) {
      *out = *exact;
      return true;
    }
    if (overflow) {
      error = "time stamp " + field + " = " + std::to_string(slot_values_.integers[time_slot_]) +
              " is beyond the int64 µs range";
      return false;
    }
  }
  const double us = slot_values_.values[time_slot_] * us_per_unit;
  if (!(std::abs(us) < 9.2e18)) {
    error = "time stamp " + field + " = " + shortest_number_text(slot_values_.values[time_slot_]) +
            " is beyond the int64 µs range";
    return false;
  }
  *out = std::llround(us);
  return true;
}

bool LcmUserImuDecoder::append(std::span<const unsigned char> message, bool drop_non_finite,
                               ImuSampleColumns& samples, std::string& error) {
  if (!decoder_.decode(message, slot_values_, error)) {
    error =
        "the message does not decode as " + type_name() + " (" + definition_path_ + "): " + error;
    return false;
  }
  // The used values in SI (a finite value times its scale may still overflow) and the stamp.
  std::array<double, 6> si{};
  std::int64_t non_finite = 0;
  std::string first_bad;
  const auto check = [&](double v, std::size_t slot) {
    if (std::isfinite(v)) return;
    if (non_finite++ == 0) {
      first_bad = decoder_.slot_path(slot) + (std::isnan(v) ? " (NaN)" : " (Inf)");
      if (std::isfinite(slot_values_.values[slot])) first_bad += " after scaling to SI";
    }
  };
  check(slot_values_.values[time_slot_], time_slot_);
  for (std::size_t c = 0; c < 6; ++c) {
    si[c] = slot_values_.values[value_slots_[c]] * scale_to_si_[c];
    check(si[c], value_slots_[c]);
  }
  if (non_finite > 0) {
    if (!drop_non_finite) {
      error = "non-finite value in " + first_bad;
      return false;
    }
    samples.non_finite_dropped += non_finite;
    ++samples.rows_dropped;
    return true;
  }
  std::int64_t utime_us = 0;
  if (!stamp_us(&utime_us, error)) return false;
  samples.utime_us.push_back(utime_us);
  for (std::size_t c = 0; c < 6; ++c) samples.values[c].push_back(si[c]);
  return true;
}

}  // namespace imunoise::io
