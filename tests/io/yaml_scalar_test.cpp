// Tests of io/yaml_scalar.h: the double-quoted YAML scalar of the YAML writers — an ordinary
// path is only quoted, quote, backslash and controls are escaped, and yaml-cpp reads every
// text back unchanged (every byte value but NUL, UTF-8 included).
#include "io/yaml_scalar.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

namespace imunoise::io {
namespace {

std::string read_back(const std::string& scalar) {
  return YAML::Load("key: " + scalar + "\n")["key"].as<std::string>();
}

TEST(YamlScalar, OrdinaryPathIsOnlyQuoted) {
  EXPECT_EQ(yaml_double_quoted("out/demo/model.yaml"), "\"out/demo/model.yaml\"");
  EXPECT_EQ(yaml_double_quoted(""), "\"\"");
}

TEST(YamlScalar, QuoteBackslashAndControlsAreEscaped) {
  EXPECT_EQ(yaml_double_quoted("C:\\a \"b\": #c"), "\"C:\\\\a \\\"b\\\": #c\"");
  EXPECT_EQ(yaml_double_quoted("a\nb\rc\td\x01\x1f\x7f"), "\"a\\nb\\rc\\td\\x01\\x1f\\x7f\"");
  EXPECT_EQ(yaml_double_quoted("ünïcode"), "\"ünïcode\"");
}

TEST(YamlScalar, EveryTextReadsBackUnchanged) {
  std::string all;
  for (int byte = 1; byte < 0x80; ++byte) all += static_cast<char>(byte);
  for (const std::string& text :
       {all, std::string(" leading"), std::string("trailing "), std::string("null"),
        std::string("- a: [b], {c}, &d *e !f %g @h `i` |j >k 'l'"), std::string("模型.yaml")}) {
    SCOPED_TRACE(text);
    EXPECT_EQ(read_back(yaml_double_quoted(text)), text);
  }
}

TEST(YamlScalar, ControlCharactersAreFound) {
  EXPECT_FALSE(has_control_character("out/demo/model.yaml"));
  EXPECT_FALSE(has_control_character("ünïcode: \"#\\"));
  EXPECT_TRUE(has_control_character("a\nb"));
  EXPECT_TRUE(has_control_character("a\tb"));
  EXPECT_TRUE(has_control_character("\x7f"));
}

}  // namespace
}  // namespace imunoise::io
