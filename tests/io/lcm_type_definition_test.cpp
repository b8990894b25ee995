// Tests of io/lcm_type_definition.h: the parser of users' own LCM types, read at run time
// (the test types are in tests/io/lcm_user_types/): members, dimensions and constants, located
// errors for malformed definitions, the structs of a file, and robustness on mutated
// definitions.
#include "io/lcm_type_definition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_user_types_test_support.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using namespace lcm_user_types_test;  // the test types, a decoder of one, random messages

std::string write_definition(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("lcmdef") / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

TEST(LcmTypeDefinition, ParsesMembersDimensionsAndSkipsConstants) {
  const LcmTypeFile prims = read_lcm_type_definition(type_file("usertest_primitives.lcm"));
  ASSERT_EQ(prims.structs.size(), 1u);
  const LcmStructType& p = prims.structs[0];
  EXPECT_EQ(p.full_name(), "usertest.primitives_t");
  std::vector<std::string> names;
  for (const LcmMember& m : p.members) names.push_back(m.name);
  EXPECT_THAT(names, ::testing::ElementsAre("i8", "i16", "i32", "i64", "raw_byte", "f32", "f64",
                                            "label", "flag", "a", "b", "c", "last"));
  EXPECT_TRUE(p.members[10].dimensions.empty());  // b: "double a, b, c[2]"
  ASSERT_EQ(p.members[11].dimensions.size(), 1u);
  EXPECT_EQ(p.members[11].dimensions[0].fixed_size, 2);

  const LcmTypeFile arrays = read_lcm_type_definition(type_file("usertest_arrays.lcm"));
  const LcmMember& mixed = arrays.structs[0].members[6];
  ASSERT_EQ(mixed.name, "mixed");
  ASSERT_EQ(mixed.dimensions.size(), 2u);
  EXPECT_FALSE(mixed.dimensions[0].variable);
  EXPECT_TRUE(mixed.dimensions[1].variable);
  EXPECT_EQ(mixed.dimensions[1].size_member, 0u);                           // n
  EXPECT_EQ(arrays.structs[0].members.back().dimensions[0].fixed_size, 4);  // [0x4]

  const LcmTypeFile nested = read_lcm_type_definition(type_file("usertest_nested.lcm"));
  const LcmStructType& sample = nested.structs[nested.find_struct("sample_t")];
  EXPECT_EQ(nested.structs[sample.members[2].struct_index].name, "vec3_t");    // usertest.vec3_t
  EXPECT_EQ(nested.structs[sample.members[5].struct_index].name, "status_t");  // defined later
}

TEST(LcmTypeDefinition, MalformedDefinitionsAreErrorsWithFileLineAndColumn) {
  struct Case {
    const char* text;
    const char* where;  // ":LINE:COL:" or ": " for file-level problems
    const char* problem;
  };
  const Case cases[] = {
      {"struct a {\n  dubble x;\n}", ":2:3: ", "unknown type 'dubble' of member 'x'"},
      {"struct a {\n  other.vec_t x;\n}", ":2:3: ", "types from other files are not supported"},
      {"struct a {\n  double x\n  double y;\n}",
       ":2:11: ", "expected ';' after member 'x', found 'double'"},
      {"struct a {\n  double x[n];\n}", ":2:12: ", "array size 'n' is not an earlier member"},
      {"struct a { double x[n]; int32_t n; }", ":1:21: ", "is not an earlier member"},
      {"struct a { double n; double x[n]; }", ":1:31: ", "must be a scalar int8_t"},
      {"struct a { int32_t n[2]; double x[n]; }", ":1:35: ", "(an array)"},
      {"struct a {\n /* open\n double x; }", ":2:2: ", "unterminated /* comment"},
      {"", ": ", "no struct defined in the file"},
      {"// only a comment\n", ": ", "no struct defined in the file"},
      {"package p;", ": ", "no struct defined in the file"},
      {"struct a { double x; double x; }", ":1:29: ", "member 'x' is declared twice"},
      {"struct a { double x; }\nstruct a { double y; }", ":2:8: ", "struct 'a' is defined twice"},
      {"struct a { double x[0]; }", ":1:21: ", "array size 0 is outside"},
      {"struct a { double x[-3]; }", ":1:21: ", "invalid array size '-3'"},
      {"struct a { double x[3; }", ":1:22: ", "expected ']' after the array size, found ';'"},
      {"struct a { int32_t n; a children[n]; }", ":1:23: ", "recursive types are not supported"},
      {"struct a { b x; }\nstruct b { a y; }", ":", "recursive types are not supported"},
      {"struct a { double x@; }", ":1:20: ", "unexpected character '@'"},
      {"struct a { const string S = 1; }", ":1:18: ", "invalid type for a constant"},
      {"struct a { const int32_t K = 1.5; }", ":1:30: ", "expected an integer value, found '1.5'"},
      {"struct a { double x;", ":1:1: ", "struct 'a' has no closing '}'"},
      {"struct a { enum e { A = 1 }; }", ":1:12: ", "enums are not supported"},
      {"struct 9a { double x; }", ":1:8: ", "invalid struct name '9a'"},
      {"strukt a { double x; }", ":1:1: ", "expected 'package' or 'struct', found 'strukt'"},
      {"struct a { double x; } ;", ":1:24: ", "expected 'package' or 'struct', found ';'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_definition("bad.lcm", c.text);
    const std::string message = test::error_of([&] { read_lcm_type_definition(path); });
    EXPECT_THAT(message, HasSubstr(path + c.where)) << c.text;
    EXPECT_THAT(message, HasSubstr(c.problem)) << c.text;
  }
}

TEST(LcmTypeDefinition, NulByteInTheFileIsALocatedError) {
  const std::string path =
      write_definition("nul.lcm", std::string("struct a {\n\0 double x; }", 24));
  EXPECT_THAT(test::error_of([&] { read_lcm_type_definition(path); }),
              HasSubstr(path + ":2:1: unexpected character byte \\x00"));
}

TEST(LcmTypeDefinition, StructNotFoundListsTheStructsOfTheFile) {
  const LcmTypeFile file = read_lcm_type_definition(type_file("usertest_nested.lcm"));
  const std::string message = test::error_of([&] { file.find_struct("imu_t"); });
  EXPECT_THAT(message, HasSubstr(type_file("usertest_nested.lcm") + ": no struct 'imu_t'"));
  EXPECT_THAT(message, HasSubstr("usertest.vec3_t, usertest.sample_t, usertest.status_t"));
  EXPECT_THAT(test::error_of([&] { file.find_struct(""); }),
              HasSubstr("defines 3 structs (usertest.vec3_t, usertest.sample_t, "
                        "usertest.status_t): name the one to use"));
  EXPECT_THAT(test::error_of([&] { read_lcm_type_definition("/nonexistent/x.lcm"); }),
              HasSubstr("/nonexistent/x.lcm: cannot open"));
}

TEST(LcmTypeDefinition, NeverCrashesOnMutatedDefinitions) {
  // Byte flips, deletions and insertions of the characters that matter to the grammar; every
  // outcome must be a parse or an InputError (anything else escapes and fails the test).
  std::string seed_text;
  for (const char* f : {"usertest_nested.lcm", "usertest_arrays.lcm", "usertest_primitives.lcm"}) {
    std::ifstream in(type_file(f), std::ios::binary);
    seed_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    std::mt19937_64 rng(11);
    static constexpr char kPieces[] = "{}[];,=./*\n n x0-9\"\xff";
    int parsed = 0, rejected = 0;
    for (int round = 0; round < 400; ++round) {
      std::string text = seed_text;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t pos = rng() % text.size();
        switch (rng() % 3) {
          case 0:
            text[pos] = kPieces[rng() % (sizeof kPieces - 1)];
            break;
          case 1:
            text.erase(pos, 1 + rng() % 8);
            break;
          default:
            text.insert(pos, 1, kPieces[rng() % (sizeof kPieces - 1)]);
        }
      }
      try {
        const LcmTypeFile file = parse_lcm_type_definition(text, "mutated.lcm");
        for (std::size_t i = 0; i < file.structs.size(); ++i) lcm_fingerprint(file, i);
        ++parsed;
      } catch (const InputError& error) {
        EXPECT_THAT(error.what(), HasSubstr("mutated.lcm"));
        ++rejected;
      }
    }
    EXPECT_GT(rejected, 0) << f;
    EXPECT_GT(parsed, 0) << f;
  }
}

}  // namespace
}  // namespace imunoise::io
