/// @file
/// @brief Test-side XML well-formedness checker (header-only, no dependency): used to check
/// that every SVG the report code writes parses as XML.
///
/// Checks: UTF-8 and XML characters; an optional XML declaration first; exactly one root
/// element; start/end tags balanced and correctly nested; names; attributes quoted, without
/// '<' and not repeated within a tag; references only &amp; &lt; &gt; &quot; &apos; &#N; &#xN;
/// (to XML characters); comments (no "--" inside), processing instructions, CDATA sections,
/// a DOCTYPE before the root (skipped, internal subset included); no "]]>" in text and only
/// whitespace outside the root. Namespaces and DTD validity are not checked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::test {

struct XmlCheckResult {
  bool ok = false;
  std::string message;               ///< "line L, column C: what" when !ok, "" otherwise
  std::size_t line = 0, column = 0;  ///< 1-based position of the error (column in bytes)
  std::string root;                  ///< name of the root element when ok
  std::size_t elements = 0;          ///< number of elements when ok
};

namespace xml_check_detail {

class Checker {
 public:
  explicit Checker(std::string_view text) : s_(text) {}

  XmlCheckResult run() {
    XmlCheckResult result;
    if (!check_utf8()) return fail(result);
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
    if (starts_with("<?xml") && pos_ + 5 < s_.size() && is_space(s_[pos_ + 5])) {
      if (!declaration()) return fail(result);
    }
    bool seen_root = false, seen_doctype = false;
    while (true) {
      skip_space();
      if (pos_ >= s_.size()) break;
      if (s_[pos_] != '<') {
        error_ = seen_root ? "text after the root element" : "text before the root element";
        return fail(result);
      }
      if (starts_with("<!--")) {
        if (!comment()) return fail(result);
      } else if (starts_with("<?")) {
        if (!processing_instruction()) return fail(result);
      } else if (starts_with("<!DOCTYPE")) {
        if (seen_root || seen_doctype) {
          error_ = "DOCTYPE must come once, before the root element";
          return fail(result);
        }
        seen_doctype = true;
        if (!doctype()) return fail(result);
      } else if (seen_root) {
        error_ = "a second root element (or markup after the root)";
        return fail(result);
      } else {
        seen_root = true;
        if (!element(result.root)) return fail(result);
      }
    }
    if (!seen_root) {
      error_ = "no root element";
      return fail(result);
    }
    result.ok = true;
    result.elements = elements_;
    return result;
  }

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
  std::size_t elements_ = 0;
  std::string error_;

  XmlCheckResult fail(XmlCheckResult& r) const {
    r.ok = false;
    r.root.clear();
    r.line = 1;
    std::size_t line_start = 0;
    const std::size_t end = pos_ < s_.size() ? pos_ : s_.size();
    for (std::size_t i = 0; i < end; ++i) {
      if (s_[i] == '\n') {
        ++r.line;
        line_start = i + 1;
      }
    }
    r.column = end - line_start + 1;
    r.message =
        "line " + std::to_string(r.line) + ", column " + std::to_string(r.column) + ": " + error_;
    return r;
  }

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  static bool is_name_start(char c) {
    const auto u = static_cast<unsigned char>(c);
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' || u >= 0x80;
  }
  static bool is_name_char(char c) {
    return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
  }
  static bool is_xml_char(std::uint32_t c) {
    return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
           (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
  }
  bool starts_with(std::string_view prefix) const {
    return s_.substr(pos_, prefix.size()) == prefix;
  }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) ++pos_;
  }

  /// Whole document: valid UTF-8 of XML characters only.
  bool check_utf8() {
    for (pos_ = 0; pos_ < s_.size();) {
      const auto c = static_cast<unsigned char>(s_[pos_]);
      std::size_t n = 0;
      std::uint32_t code = 0;
      if (c < 0x80) {
        n = 1;
        code = c;
      } else if (c >= 0xC2 && c <= 0xDF) {
        n = 2;
        code = c & 0x1Fu;
      } else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        code = c & 0x0Fu;
      } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        code = c & 0x07u;
      } else {
        error_ = "invalid UTF-8 byte";
        return false;
      }
      if (pos_ + n > s_.size()) {
        error_ = "truncated UTF-8 sequence";
        return false;
      }
      for (std::size_t k = 1; k < n; ++k) {
        const auto b = static_cast<unsigned char>(s_[pos_ + k]);
        if ((b & 0xC0u) != 0x80u) {
          error_ = "invalid UTF-8 sequence";
          return false;
        }
        code = (code << 6) | (b & 0x3Fu);
      }
      static constexpr std::uint32_t kMinimum[5] = {0, 0, 0x80, 0x800, 0x10000};
      if (code < kMinimum[n] || !is_xml_char(code)) {
        error_ = "character not allowed in XML (or overlong UTF-8)";
        return false;
      }
      pos_ += n;
    }
    pos_ = 0;
    return true;
  }

  bool name(std::string* out = nullptr) {
    const std::size_t start = pos_;
    if (pos_ >= s_.size() || !is_name_start(s_[pos_])) {
      error_ = "expected a name";
      return false;
    }
    while (pos_ < s_.size() && is_name_char(s_[pos_])) ++pos_;
    if (out) *out = std::string(s_.substr(start, pos_ - start));
    return true;
  }

  /// At '&': one of the predefined entities or a character reference.
  bool reference() {
    const std::size_t semicolon = s_.find(';', pos_);
    if (semicolon == std::string_view::npos || semicolon - pos_ > 12) {
      error_ = "'&' not starting a reference (write &amp;)";
      return false;
    }
    const std::string_view ref = s_.substr(pos_ + 1, semicolon - pos_ - 1);
    if (ref == "amp" || ref == "lt" || ref == "gt" || ref == "quot" || ref == "apos") {
      pos_ = semicolon + 1;
      return true;
    }
    if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string_view digits = ref.substr(hex ? 2 : 1);
      std::uint64_t value = 0;
      bool ok = !digits.empty() && digits.size() <= 8;
      for (char c : digits) {
        if (!ok) break;
        int d = -1;
        if (c >= '0' && c <= '9') d = c - '0';
        if (hex && c >= 'a' && c <= 'f') d = c - 'a' + 10;
        if (hex && c >= 'A' && c <= 'F') d = c - 'A' + 10;
        ok = d >= 0;
        value = value * (hex ? 16 : 10) + static_cast<std::uint64_t>(d < 0 ? 0 : d);
      }
      if (ok && value <= 0x10FFFF && is_xml_char(static_cast<std::uint32_t>(value))) {
        pos_ = semicolon + 1;
        return true;
      }
      error_ = "bad character reference &" + std::string(ref) + ";";
      return false;
    }
    error_ = "unknown entity &" + std::string(ref) + ";";
    return false;
  }

  bool attribute_value() {
    if (pos_ >= s_.size() || (s_[pos_] != '"' && s_[pos_] != '\'')) {
      error_ = "attribute value must be quoted";
      return false;
    }
    const char quote = s_[pos_++];
    while (pos_ < s_.size() && s_[pos_] != quote) {
      if (s_[pos_] == '<') {
        error_ = "'<' in an attribute value";
        return false;
      }
      if (s_[pos_] == '&') {
        if (!reference()) return false;
      } else {
        ++pos_;
      }
    }
    if (pos_ >= s_.size()) {
      error_ = "unterminated attribute value";
      return false;
    }
    ++pos_;
    return true;
  }

  /// Attributes up to '>' or '/>' (or '?>' for the declaration); leaves pos_ at that end.
  bool attributes(bool* empty_element, bool declaration = false) {
    std::vector<std::string> seen;
    while (true) {
      const std::size_t before = pos_;
      skip_space();
      if (pos_ >= s_.size()) {
        error_ = "unterminated tag";
        return false;
      }
      if (declaration ? starts_with("?>") : (starts_with("/>") || s_[pos_] == '>')) {
        if (empty_element) *empty_element = s_[pos_] == '/';
        pos_ += s_[pos_] == '>' ? 1 : 2;
        return true;
      }
      if (pos_ == before) {
        error_ = "expected whitespace before an attribute";
        return false;
      }
      std::string attribute;
      const std::size_t attribute_start = pos_;
      if (!name(&attribute)) {
        error_ = "expected an attribute name, '>' or '/>'";
        return false;
      }
      for (const auto& other : seen) {
        if (other == attribute) {
          pos_ = attribute_start;
          error_ = "duplicate attribute '" + attribute + "'";
          return false;
        }
      }
      seen.push_back(attribute);
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != '=') {
        error_ = "expected '=' after attribute '" + attribute + "'";
        return false;
      }
      ++pos_;
      skip_space();
      if (!attribute_value()) return false;
    }
  }

  bool declaration() {
    pos_ += 5;
    if (!attributes(nullptr, true)) return false;
    return true;
  }

  bool comment() {
    const std::size_t start = pos_;
    const std::size_t end = s_.find("--", start + 4);
    if (end == std::string_view::npos) {
      error_ = "unterminated comment";
      return false;
    }
    if (end + 2 >= s_.size() || s_[end + 2] != '>') {
      pos_ = end;
      error_ = "\"--\" inside a comment";
      return false;
    }
    pos_ = end + 3;
    return true;
  }

  bool processing_instruction() {
    pos_ += 2;
    std::string target;
    if (!name(&target)) return false;
    if (target.size() == 3 && (target[0] | 0x20) == 'x' && (target[1] | 0x20) == 'm' &&
        (target[2] | 0x20) == 'l') {
      error_ = "XML declaration not at the start of the document";
      return false;
    }
    const std::size_t end = s_.find("?>", pos_);
    if (end == std::string_view::npos) {
      error_ = "unterminated processing instruction";
      return false;
    }
    pos_ = end + 2;
    return true;
  }

  bool doctype() {
    int depth = 0;
    char quote = 0;
    for (pos_ += 9; pos_ < s_.size(); ++pos_) {
      const char c = s_[pos_];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '[') {
        ++depth;
      } else if (c == ']') {
        --depth;
      } else if (c == '>' && depth == 0) {
        ++pos_;
        return true;
      }
    }
    error_ = "unterminated DOCTYPE";
    return false;
  }

  /// The root element and everything in it (iterative: no recursion on deep nesting).
  bool element(std::string& root) {
    std::vector<std::string> open;
    while (true) {
      // pos_ at '<' of a start tag
      ++pos_;
      std::string tag;
      if (!name(&tag)) return false;
      ++elements_;
      if (open.empty()) root = tag;
      bool empty = false;
      if (!attributes(&empty)) return false;
      if (!empty) open.push_back(tag);
      // content until the next start tag, or the end of the root
      while (!open.empty()) {
        if (pos_ >= s_.size()) {
          error_ = "unclosed element <" + open.back() + ">";
          return false;
        }
        const char c = s_[pos_];
        if (c == '&') {
          if (!reference()) return false;
        } else if (c != '<') {
          if (starts_with("]]>")) {
            error_ = "\"]]>\" in text";
            return false;
          }
          ++pos_;
        } else if (starts_with("</")) {
          const std::size_t tag_start = pos_;
          pos_ += 2;
          std::string closing;
          if (!name(&closing)) return false;
          skip_space();
          if (pos_ >= s_.size() || s_[pos_] != '>') {
            error_ = "expected '>' to end </" + closing + ">";
            return false;
          }
          if (closing != open.back()) {
            pos_ = tag_start;
            error_ = "</" + closing + "> does not close <" + open.back() + ">";
            return false;
          }
          ++pos_;
          open.pop_back();
        } else if (starts_with("<!--")) {
          if (!comment()) return false;
        } else if (starts_with("<![CDATA[")) {
          const std::size_t end = s_.find("]]>", pos_ + 9);
          if (end == std::string_view::npos) {
            error_ = "unterminated CDATA section";
            return false;
          }
          pos_ = end + 3;
        } else if (starts_with("<?")) {
          if (!processing_instruction()) return false;
        } else if (starts_with("<!")) {
          error_ = "markup declaration inside an element";
          return false;
        } else {
          break;  // a child start tag
        }
      }
      if (open.empty()) return true;
    }
  }
};

}  // namespace xml_check_detail

/// The `<svg>…</svg>` elements of a text (an HTML page with inline plots), in order; each is
/// a document check_xml can parse.
inline std::vector<std::string> svg_elements(std::string_view text) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while ((at = text.find("<svg", at)) != std::string_view::npos) {
    const std::size_t end = text.find("</svg>", at);
    if (end == std::string_view::npos) break;
    out.emplace_back(text.substr(at, end + 6 - at));
    at = end + 6;
  }
  return out;
}

/// Checks that TEXT is a well-formed XML document (see the file comment for what is checked).
inline XmlCheckResult check_xml(std::string_view text) {
  return xml_check_detail::Checker(text).run();
}

}  // namespace imunoise::test
