/// @file
/// @brief The parser of LCM type-definition files (see lcm_type_definition.h): a lexer, a
/// recursive-descent parser checking every rule with a located InputError, and the resolution
/// of nested struct types.
#include "io/lcm_type_definition.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "io/lcm_type_definition_internal.h"

namespace imunoise::io {
namespace {

using detail::is_identifier;
using detail::is_size_type;
using detail::kMaxDimensions;
using detail::kMaxNestingDepth;
using detail::primitive_named;

constexpr std::size_t kMaxDefinitionBytes = std::size_t{1} << 20;

// ---------------------------------------------------------------------------------------------
// Text helpers

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
    // Built with append() only: GCC 12 raises a false -Wrestrict on `"'" + std::string(…)`.
    std::string out = "'";
    out.append(token_.text.substr(0, kShown)).append(token_.text.size() > kShown ? "…'" : "'");
    return out;
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public

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
}  // namespace imunoise::io
