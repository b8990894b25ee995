// Tests of io/lcm_type_definition.h: users' own LCM types read at run time. The test types in
// tests/io/lcm_user_types/ are also compiled by lcm-gen (tests/CMakeLists.txt), so the
// fingerprint is checked against the generated getHash() and the decoder against messages the
// generated test::lcm_encode() wrote. Also: located errors for malformed definitions, robustness on
// mutated definitions and corrupted messages, and read_lcm_imu_log with a user type on logs
// written by lcm::LogFile.
#include "io/lcm_type_definition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <delta_imu_t.hpp>
#include <filesystem>
#include <fstream>
#include <imunoise/imu_sample_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <usertest/arrays_t.hpp>
#include <usertest/ins_t.hpp>
#include <usertest/primitives_t.hpp>
#include <usertest/sample_t.hpp>
#include <usertest/scalar_imu_t.hpp>
#include <usertest/status_t.hpp>
#include <usertest/vec3_t.hpp>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/lcm_field_decoder.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_log.h"
#include "io/lcm_user_imu_decoder.h"
#include "lcm_test_support.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using Bytes = test::LcmBytes;
using LogWriter = test::LcmLogFileWriter;

constexpr std::int64_t kEpochUs = 1'700'000'000'000'000;  // 2023-11-14, µs since the epoch
constexpr std::int64_t kStepUs = 5'000;                   // 200 Hz
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kG = 9.80665;

std::string type_file(const std::string& name) {
  return std::string(IMUNOISE_SOURCE_DIR) + "/tests/io/lcm_user_types/" + name;
}

LcmFieldDecoder decoder_for(const std::string& file, const std::string& type) {
  LcmTypeFile parsed = read_lcm_type_definition(type_file(file));
  const std::size_t index = parsed.find_struct(type);
  return LcmFieldDecoder(std::move(parsed), index);
}

/// Every leaf of `message`, by path (fails the test when it does not decode).
std::map<std::string, LcmFieldValue> decode_by_path(LcmFieldDecoder& decoder,
                                                    const Bytes& message) {
  std::vector<LcmFieldValue> values;
  std::string error;
  EXPECT_TRUE(decoder.decode_all(message, values, error)) << error;
  std::map<std::string, LcmFieldValue> out;
  for (LcmFieldValue& v : values) {
    const std::string path = v.path;
    EXPECT_TRUE(out.emplace(path, std::move(v)).second) << "duplicate path " << path;
  }
  return out;
}

// ---- random values (fixed seed): full-range integers, doubles and floats of any finite bit
// pattern, so a byte-order or width mistake cannot hide.
class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  std::uint64_t bits() { return rng_(); }
  template <typename Int>
  Int integer() {
    return static_cast<Int>(bits());
  }
  double real() {
    while (true) {
      const double v = std::bit_cast<double>(bits());
      if (std::isfinite(v)) return v;
    }
  }
  float real32() {
    while (true) {
      const float v = std::bit_cast<float>(static_cast<std::uint32_t>(bits()));
      if (std::isfinite(v)) return v;
    }
  }
  int below(int n) { return static_cast<int>(bits() % static_cast<std::uint64_t>(n)); }
  std::string text() {
    std::string s(static_cast<std::size_t>(below(12)), ' ');
    for (char& c : s) c = static_cast<char>('a' + below(26));
    return s;
  }

 private:
  std::mt19937_64 rng_;
};

usertest::primitives_t random_primitives(Random& r) {
  usertest::primitives_t m{};
  m.i8 = r.integer<std::int8_t>();
  m.i16 = r.integer<std::int16_t>();
  m.i32 = r.integer<std::int32_t>();
  m.i64 = r.integer<std::int64_t>();
  m.raw_byte = r.integer<std::uint8_t>();
  m.f32 = r.real32();
  m.f64 = r.real();
  m.label = r.text();
  m.flag = static_cast<std::int8_t>(r.below(2));
  m.a = r.real();
  m.b = r.real();
  m.c[0] = r.real();
  m.c[1] = r.real();
  m.last = r.integer<std::int16_t>();
  return m;
}

usertest::arrays_t random_arrays(Random& r) {
  usertest::arrays_t m{};
  m.n = r.below(4);
  m.m = static_cast<std::int8_t>(r.below(3));
  m.count64 = r.below(5);
  for (double& v : m.fixed3) v = r.real();
  for (int i = 0; i < m.n; ++i) m.var.push_back(r.real32());
  for (auto& row : m.grid) {
    for (std::int64_t& v : row) v = r.integer<std::int64_t>();
  }
  m.mixed.resize(3);  // ecosystem.md: the outer vector of a [3][n] array is not pre-sized
  for (auto& row : m.mixed) {
    for (int i = 0; i < m.n; ++i) row.push_back(r.real());
  }
  m.var_var.resize(static_cast<std::size_t>(m.n));
  for (auto& row : m.var_var) {
    for (int j = 0; j < m.m; ++j) row.push_back(r.integer<std::int16_t>());
  }
  m.var_fixed.resize(static_cast<std::size_t>(m.m));
  for (auto& row : m.var_fixed) row = {r.integer<std::int32_t>(), r.integer<std::int32_t>()};
  for (std::string& s : m.names) s = r.text();
  for (int j = 0; j < m.m; ++j) {
    m.words.push_back(r.text());
    m.flags.push_back(static_cast<std::int8_t>(r.below(2)));
  }
  for (int k = 0; k < m.count64; ++k) m.raw.push_back(r.integer<std::uint8_t>());
  for (std::int32_t& v : m.hex_sized) v = r.integer<std::int32_t>();
  return m;
}

usertest::vec3_t random_vec3(Random& r) {
  usertest::vec3_t v{};
  for (double& x : v.v) x = r.real();
  return v;
}

usertest::sample_t random_sample(Random& r) {
  usertest::sample_t m{};
  m.utime = r.integer<std::int64_t>();
  m.gyro = random_vec3(r);
  m.accel = random_vec3(r);
  m.n_history = r.below(4);
  for (int i = 0; i < m.n_history; ++i) m.history.push_back(random_vec3(r));
  m.status.n_codes = static_cast<std::int8_t>(r.below(3));
  for (int i = 0; i < m.status.n_codes; ++i) m.status.codes.push_back(r.integer<std::int16_t>());
  m.status.ok = static_cast<std::int8_t>(r.below(2));
  m.pair[0] = random_vec3(r);
  m.pair[1] = random_vec3(r);
  m.frame = r.text();
  return m;
}

// ---- exact comparison of one decoded leaf with the value the generated class held

void expect_double(const std::map<std::string, LcmFieldValue>& got, const std::string& path,
                   double want) {
  const auto it = got.find(path);
  ASSERT_NE(it, got.end()) << path;
  EXPECT_EQ(it->second.type, LcmPrimitive::kDouble) << path;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(it->second.value), std::bit_cast<std::uint64_t>(want))
      << path;
}
void expect_float(const std::map<std::string, LcmFieldValue>& got, const std::string& path,
                  float want) {
  const auto it = got.find(path);
  ASSERT_NE(it, got.end()) << path;
  EXPECT_EQ(it->second.type, LcmPrimitive::kFloat) << path;
  EXPECT_EQ(std::bit_cast<std::uint32_t>(static_cast<float>(it->second.value)),
            std::bit_cast<std::uint32_t>(want))
      << path;
}
void expect_integer(const std::map<std::string, LcmFieldValue>& got, const std::string& path,
                    std::int64_t want, LcmPrimitive type) {
  const auto it = got.find(path);
  ASSERT_NE(it, got.end()) << path;
  EXPECT_EQ(it->second.type, type) << path;
  EXPECT_EQ(it->second.integer, want) << path;
  EXPECT_EQ(it->second.value, static_cast<double>(want)) << path;
}
void expect_text(const std::map<std::string, LcmFieldValue>& got, const std::string& path,
                 const std::string& want) {
  const auto it = got.find(path);
  ASSERT_NE(it, got.end()) << path;
  EXPECT_EQ(it->second.type, LcmPrimitive::kString) << path;
  EXPECT_EQ(it->second.text, want) << path;
}
std::string at(const std::string& name, std::size_t i) {
  return name + "[" + std::to_string(i) + "]";
}
std::string at(const std::string& name, std::size_t i, std::size_t j) {
  return at(name, i) + "[" + std::to_string(j) + "]";
}

// ---- files and logs

std::string write_definition(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("lcmdef") / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

usertest::ins_t ins_sample(int i) {
  usertest::ins_t m{};
  m.utime = kEpochUs + i * kStepUs;
  m.device_time = 1000 + i;
  m.quat[0] = 1.0;
  for (int a = 0; a < 3; ++a) {
    m.gyro[a] = (a + 1) * 1e-3 + i * std::sqrt(2.0) * 1e-7 + 1.0 / (7 + a);
    m.accel[a] = (a == 2 ? -9.80665 : 0.01 * (a + 1)) + i * 1e-6 / 3.0;
    m.mag[a] = 0.2 * a;
  }
  m.pressure = 101325.0 + i;
  m.rel_alt = -1.5;
  return m;
}

LcmUserType ins_user_type() {
  LcmUserType t;
  t.definition_path = type_file("usertest_ins.lcm");
  t.type_name = "usertest.ins_t";
  t.gyro_fields = {"gyro"};
  t.accel_fields = {"accel"};
  return t;
}

std::filesystem::path ins_log(const std::string& name, int count) {
  const auto path = test::make_temp_dir("lcmuser") / name;
  LogWriter writer(path);
  for (int i = 0; i < count; ++i) writer.write("INS", ins_sample(i));
  return path;
}

LcmReadOptions with_user_type(const LcmUserType& t, bool drop_non_finite = false) {
  LcmReadOptions options;
  options.drop_non_finite = drop_non_finite;
  options.user_type = t;
  return options;
}

// ---------------------------------------------------------------------------------------------
// Fingerprint

TEST(LcmTypeFingerprint, EqualsTheGeneratedGetHashForEveryTestType) {
  struct Case {
    const char* file;
    const char* type;
    std::int64_t generated;
  };
  const Case cases[] = {
      {"usertest_primitives.lcm", "usertest.primitives_t", usertest::primitives_t::getHash()},
      {"usertest_arrays.lcm", "usertest.arrays_t", usertest::arrays_t::getHash()},
      {"usertest_nested.lcm", "usertest.vec3_t", usertest::vec3_t::getHash()},
      {"usertest_nested.lcm", "usertest.sample_t", usertest::sample_t::getHash()},
      {"usertest_nested.lcm", "status_t", usertest::status_t::getHash()},
      {"usertest_ins.lcm", "", usertest::ins_t::getHash()},
      {"usertest_scalar_imu.lcm", "scalar_imu_t", usertest::scalar_imu_t::getHash()},
      {"delta_imu.lcm", "delta_imu_t", delta_imu_t::getHash()},
  };
  for (const Case& c : cases) {
    const LcmTypeFile file = read_lcm_type_definition(type_file(c.file));
    const std::uint64_t ours = lcm_fingerprint(file, file.find_struct(c.type));
    EXPECT_EQ(ours, static_cast<std::uint64_t>(c.generated)) << c.file << " " << c.type;
  }
}

TEST(LcmTypeFingerprint, OurOwnImuSampleDefinitionMatchesItsGeneratedType) {
  // The same parser on lcmtypes/ (the generated header is the one imunoise itself uses).
  const LcmTypeFile file = read_lcm_type_definition(std::string(IMUNOISE_SOURCE_DIR) +
                                                    "/lcmtypes/imunoise_imu_sample_t.lcm");
  EXPECT_EQ(lcm_fingerprint(file, file.find_struct("imunoise.imu_sample_t")),
            static_cast<std::uint64_t>(imunoise::imu_sample_t::getHash()));
}

TEST(LcmTypeFingerprint, EncodedMessagesStartWithIt) {
  Random r(7);
  const Bytes bytes = test::lcm_encode(random_sample(r));
  LcmFieldDecoder decoder = decoder_for("usertest_nested.lcm", "sample_t");
  std::uint64_t head = 0;
  for (int i = 0; i < 8; ++i) head = (head << 8) | bytes[static_cast<std::size_t>(i)];
  EXPECT_EQ(head, decoder.fingerprint());
}

// ---------------------------------------------------------------------------------------------
// Parsing

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

// ---------------------------------------------------------------------------------------------
// Decoding

TEST(LcmTypeDecode, EveryPrimitiveRoundTripsExactly) {
  Random r(1);
  LcmFieldDecoder decoder = decoder_for("usertest_primitives.lcm", "");
  for (int i = 0; i < 200; ++i) {
    usertest::primitives_t m = random_primitives(r);
    if (i == 0) {  // the extremes
      m.i8 = INT8_MIN;
      m.i16 = INT16_MIN;
      m.i32 = INT32_MIN;
      m.i64 = INT64_MIN;
      m.raw_byte = 255;
      m.f32 = -std::numeric_limits<float>::denorm_min();
      m.f64 = std::numeric_limits<double>::max();
      m.label = "";
    }
    const auto got = decode_by_path(decoder, test::lcm_encode(m));
    EXPECT_EQ(got.size(), 14u);
    expect_integer(got, "i8", m.i8, LcmPrimitive::kInt8);
    expect_integer(got, "i16", m.i16, LcmPrimitive::kInt16);
    expect_integer(got, "i32", m.i32, LcmPrimitive::kInt32);
    expect_integer(got, "i64", m.i64, LcmPrimitive::kInt64);
    expect_integer(got, "raw_byte", m.raw_byte, LcmPrimitive::kByte);
    expect_float(got, "f32", m.f32);
    expect_double(got, "f64", m.f64);
    expect_text(got, "label", m.label);
    expect_integer(got, "flag", m.flag, LcmPrimitive::kBoolean);
    expect_double(got, "a", m.a);
    expect_double(got, "b", m.b);
    expect_double(got, "c[0]", m.c[0]);
    expect_double(got, "c[1]", m.c[1]);
    expect_integer(got, "last", m.last, LcmPrimitive::kInt16);
  }
}

TEST(LcmTypeDecode, FixedVariableAndMultiDimensionalArraysRoundTripExactly) {
  Random r(2);
  LcmFieldDecoder decoder = decoder_for("usertest_arrays.lcm", "arrays_t");
  for (int i = 0; i < 200; ++i) {
    const usertest::arrays_t m = random_arrays(r);
    const auto got = decode_by_path(decoder, test::lcm_encode(m));
    const std::size_t n = static_cast<std::size_t>(m.n), k = static_cast<std::size_t>(m.m);
    EXPECT_EQ(got.size(), 3 + 3 + n + 6 + 3 * n + n * k + 2 * k + 2 + 2 * k +
                              static_cast<std::size_t>(m.count64) + 4);
    expect_integer(got, "n", m.n, LcmPrimitive::kInt32);
    expect_integer(got, "m", m.m, LcmPrimitive::kInt8);
    expect_integer(got, "count64", m.count64, LcmPrimitive::kInt64);
    for (std::size_t a = 0; a < 3; ++a) expect_double(got, at("fixed3", a), m.fixed3[a]);
    for (std::size_t a = 0; a < n; ++a) expect_float(got, at("var", a), m.var[a]);
    for (std::size_t a = 0; a < 2; ++a) {
      for (std::size_t b = 0; b < 3; ++b) {
        expect_integer(got, at("grid", a, b), m.grid[a][b], LcmPrimitive::kInt64);
      }
    }
    for (std::size_t a = 0; a < 3; ++a) {
      for (std::size_t b = 0; b < n; ++b) expect_double(got, at("mixed", a, b), m.mixed[a][b]);
    }
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < k; ++b) {
        expect_integer(got, at("var_var", a, b), m.var_var[a][b], LcmPrimitive::kInt16);
      }
    }
    for (std::size_t a = 0; a < k; ++a) {
      for (std::size_t b = 0; b < 2; ++b) {
        expect_integer(got, at("var_fixed", a, b), m.var_fixed[a][b], LcmPrimitive::kInt32);
      }
      expect_text(got, at("words", a), m.words[a]);
      expect_integer(got, at("flags", a), m.flags[a], LcmPrimitive::kBoolean);
    }
    for (std::size_t a = 0; a < 2; ++a) expect_text(got, at("names", a), m.names[a]);
    for (std::size_t a = 0; a < m.raw.size(); ++a) {
      expect_integer(got, at("raw", a), m.raw[a], LcmPrimitive::kByte);
    }
    for (std::size_t a = 0; a < 4; ++a) {
      expect_integer(got, at("hex_sized", a), m.hex_sized[a], LcmPrimitive::kInt32);
    }
  }
}

TEST(LcmTypeDecode, NestedStructsRoundTripExactly) {
  Random r(3);
  LcmFieldDecoder decoder = decoder_for("usertest_nested.lcm", "usertest.sample_t");
  for (int i = 0; i < 200; ++i) {
    const usertest::sample_t m = random_sample(r);
    const auto got = decode_by_path(decoder, test::lcm_encode(m));
    expect_integer(got, "utime", m.utime, LcmPrimitive::kInt64);
    for (std::size_t a = 0; a < 3; ++a) {
      expect_double(got, at("gyro.v", a), m.gyro.v[a]);
      expect_double(got, at("accel.v", a), m.accel.v[a]);
      for (std::size_t h = 0; h < m.history.size(); ++h) {
        expect_double(got, at("history", h) + at(".v", a), m.history[h].v[a]);
      }
      expect_double(got, "pair[1].v[" + std::to_string(a) + "]", m.pair[1].v[a]);
    }
    expect_integer(got, "status.n_codes", m.status.n_codes, LcmPrimitive::kInt8);
    for (std::size_t c = 0; c < m.status.codes.size(); ++c) {
      expect_integer(got, at("status.codes", c), m.status.codes[c], LcmPrimitive::kInt16);
    }
    expect_integer(got, "status.ok", m.status.ok, LcmPrimitive::kBoolean);
    expect_text(got, "frame", m.frame);
  }
}

TEST(LcmTypeDecode, SelectedFieldsGiveTheSameValuesWithoutNames) {
  Random r(4);
  LcmFieldDecoder arrays = decoder_for("usertest_arrays.lcm", "arrays_t");
  const auto fixed3 = arrays.add_field("fixed3");  // a fixed 1-D array named whole
  ASSERT_EQ(fixed3.size(), 3u);
  EXPECT_EQ(arrays.slot_path(fixed3[2]), "fixed3[2]");
  const std::size_t grid = arrays.add_field("grid[1][2]").at(0);
  const std::size_t mixed = arrays.add_field("mixed[2][0]").at(0);
  const std::size_t count64 = arrays.add_field("count64").at(0);
  const std::size_t var = arrays.add_field("var[0]").at(0);
  LcmSlotValues values;
  std::string error;
  int decoded = 0;
  for (int i = 0; i < 100; ++i) {
    usertest::arrays_t m = random_arrays(r);
    const bool has_first = m.n > 0;
    if (!arrays.decode(test::lcm_encode(m), values, error)) {
      // var[0] and mixed[2][0] exist only when n > 0: named in the failure.
      EXPECT_FALSE(has_first);
      EXPECT_THAT(error, HasSubstr("is not in this message"));
      continue;
    }
    ++decoded;
    ASSERT_TRUE(has_first);
    for (std::size_t a = 0; a < 3; ++a) EXPECT_EQ(values.values[fixed3[a]], m.fixed3[a]);
    EXPECT_EQ(values.integers[grid], m.grid[1][2]);
    EXPECT_EQ(values.values[mixed], m.mixed[2][0]);
    EXPECT_EQ(values.integers[count64], m.count64);
    EXPECT_EQ(values.values[var], static_cast<double>(m.var[0]));
    EXPECT_EQ(values.integers[var], 0);  // float: no integer value
  }
  EXPECT_GT(decoded, 50);

  LcmFieldDecoder nested = decoder_for("usertest_nested.lcm", "sample_t");
  const auto gyro = nested.add_field("gyro.v");
  const std::size_t history = nested.add_field("history[1].v[2]").at(0);
  const std::size_t code = nested.add_field("status.codes[0]").at(0);
  EXPECT_EQ(nested.slot_path(gyro[1]), "gyro.v[1]");
  for (int i = 0; i < 100; ++i) {
    usertest::sample_t m = random_sample(r);
    const bool present = m.history.size() > 1 && !m.status.codes.empty();
    ASSERT_EQ(nested.decode(test::lcm_encode(m), values, error), present) << error;
    if (!present) continue;
    for (std::size_t a = 0; a < 3; ++a) EXPECT_EQ(values.values[gyro[a]], m.gyro.v[a]);
    EXPECT_EQ(values.values[history], m.history[1].v[2]);
    EXPECT_EQ(values.integers[code], m.status.codes[0]);
  }
}

TEST(LcmTypeDecode, BadFieldPathsAreErrorsListingTheMembers) {
  LcmFieldDecoder d = decoder_for("usertest_nested.lcm", "sample_t");
  EXPECT_THAT(test::error_of([&] { d.add_field("gyr"); }),
              HasSubstr("field 'gyr': struct 'usertest.sample_t' has no member 'gyr'; its "
                        "members: utime, gyro (vec3_t), accel (usertest.vec3_t), n_history, "
                        "history[n_history] (vec3_t)"));
  EXPECT_THAT(test::error_of([&] { d.add_field("gyro"); }),
              HasSubstr("'gyro' is a struct (vec3_t); name one of its members: v[3]"));
  EXPECT_THAT(test::error_of([&] { d.add_field("frame"); }), HasSubstr("is a string"));
  EXPECT_THAT(test::error_of([&] { d.add_field("utime.x"); }),
              HasSubstr("'utime' is of type int64_t, not a struct"));
  EXPECT_THAT(test::error_of([&] { d.add_field("gyro.v[3]"); }),
              HasSubstr("index 3 is beyond dimension 1 of 'v' (size 3)"));
  EXPECT_THAT(test::error_of([&] { d.add_field("status.codes"); }),
              HasSubstr("variable-length array is selected element by element"));
  EXPECT_THAT(test::error_of([&] { d.add_field("gyro.v[x]"); }),
              HasSubstr("bad field path 'gyro.v[x]'"));
  EXPECT_THAT(test::error_of([&] { d.add_field("gyro..v"); }), HasSubstr("bad field path"));
  EXPECT_THAT(test::error_of([&] { d.add_field(""); }), HasSubstr("bad field path"));
}

TEST(LcmTypeDecode, TruncatedMessagesAreReportedAtEveryLength) {
  Random r(5);
  LcmFieldDecoder decoder = decoder_for("usertest_arrays.lcm", "arrays_t");
  usertest::arrays_t m = random_arrays(r);
  m.n = 2;
  m.var = {1.0f, 2.0f};
  m.mixed.assign(3, {0.5, 0.25});
  m.var_var.assign(2, std::vector<std::int16_t>(static_cast<std::size_t>(m.m), 7));
  const Bytes full = test::lcm_encode(m);
  std::vector<LcmFieldValue> all;
  std::string error;
  for (std::size_t length = 0; length < full.size(); ++length) {
    const Bytes cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(length));
    EXPECT_FALSE(decoder.decode_all(cut, all, error)) << length;
    EXPECT_THAT(error, HasSubstr("byte ")) << length;
  }
  Bytes longer = full;
  longer.push_back(0);
  EXPECT_FALSE(decoder.decode_all(longer, all, error));
  EXPECT_THAT(error, HasSubstr("1 bytes left over"));
}

TEST(LcmTypeDecode, CorruptLengthsAndFingerprintsAreNamed) {
  LcmFieldDecoder decoder = decoder_for("usertest_arrays.lcm", "arrays_t");
  usertest::arrays_t m{};
  m.mixed.resize(3);
  const Bytes good = test::lcm_encode(m);  // n = m = count64 = 0
  std::vector<LcmFieldValue> all;
  std::string error;
  ASSERT_TRUE(decoder.decode_all(good, all, error)) << error;

  Bytes negative = good;
  negative[8] = 0xFF;  // n = -16777216
  EXPECT_FALSE(decoder.decode_all(negative, all, error));
  EXPECT_THAT(error, HasSubstr("size n = -16777216 of 'var' is negative"));

  Bytes huge = good;
  huge[8] = 0x7F;  // n ≈ 2^31: more floats than bytes left, refused before any allocation
  EXPECT_FALSE(decoder.decode_all(huge, all, error));
  EXPECT_THAT(error, HasSubstr("'var' needs 2130706432 × 4 bytes"));

  Bytes wrong = good;
  wrong[0] ^= 1;
  EXPECT_FALSE(decoder.decode_all(wrong, all, error));
  EXPECT_THAT(error, HasSubstr("byte 0: fingerprint 0x"));
  EXPECT_THAT(error, HasSubstr("is not the fingerprint of usertest.arrays_t"));

  // The int32 length of the empty string `label` (1: just the NUL) made 0, which LCM never
  // writes.
  LcmFieldDecoder prims = decoder_for("usertest_primitives.lcm", "");
  usertest::primitives_t p{};
  Bytes bytes = test::lcm_encode(p);
  const std::size_t label = 8 + 1 + 2 + 4 + 8 + 1 + 4 + 8;  // length of "label"
  ASSERT_EQ(bytes[label + 3], 1);
  bytes[label + 3] = 0;
  EXPECT_FALSE(prims.decode_all(bytes, all, error));
  EXPECT_THAT(error, HasSubstr("string 'label' has length 0"));
}

TEST(LcmTypeDecode, NeverCrashesOnCorruptedMessages) {
  Random r(6);
  LcmFieldDecoder arrays = decoder_for("usertest_arrays.lcm", "arrays_t");
  LcmFieldDecoder nested = decoder_for("usertest_nested.lcm", "sample_t");
  nested.add_field("history[0].v[1]");
  std::mt19937_64 rng(99);
  std::vector<LcmFieldValue> all;
  LcmSlotValues slots;
  std::string error;
  int failures = 0;
  for (int round = 0; round < 500; ++round) {
    Bytes a = test::lcm_encode(random_arrays(r));
    Bytes b = test::lcm_encode(random_sample(r));
    for (Bytes* bytes : {&a, &b}) {
      // Corrupt after the fingerprint (a wrong fingerprint stops at once), 1 to 4 bytes.
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t pos = 8 + rng() % (bytes->size() - 8);
        (*bytes)[pos] = static_cast<unsigned char>(rng());
      }
      if (rng() % 4 == 0) bytes->resize(8 + rng() % (bytes->size() - 8));
    }
    error.clear();
    if (!arrays.decode_all(a, all, error)) {
      ++failures;
      EXPECT_FALSE(error.empty());
    }
    error.clear();
    if (!nested.decode(b, slots, error)) {
      ++failures;
      EXPECT_FALSE(error.empty());
    }
  }
  EXPECT_GT(failures, 100);
}

// ---------------------------------------------------------------------------------------------
// A user's IMU type in read_lcm_imu_log

TEST(LcmUserType, InsTypeLogGivesTheMessagesValuesInSi) {
  const auto path = ins_log("ins.lcmlog", 50);
  const pipeline::Recording rec =
      read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type()));
  ASSERT_EQ(rec.sample_count(), 50u);
  ASSERT_EQ(rec.channels.size(), 6u);
  EXPECT_NEAR(rec.sample_period_s, 0.005, 1e-15);  // the median of time_s differences
  EXPECT_EQ(rec.start_time_s, static_cast<double>(kEpochUs) * 1e-6);
  for (std::size_t c = 0; c < 6; ++c) {
    const pipeline::Channel& ch = rec.channels[c];
    EXPECT_EQ(ch.name, pipeline::kImuChannelNames[c]);
    EXPECT_EQ(ch.source_column,
              "INS." + std::string(c < 3 ? "gyro" : "accel") + "[" + std::to_string(c % 3) + "]");
    EXPECT_EQ(ch.source_unit, c < 3 ? "rad/s" : "m/s^2");
    EXPECT_FALSE(ch.from_increments);
    for (int i = 0; i < 50; ++i) {
      const usertest::ins_t m = ins_sample(i);
      EXPECT_EQ(ch.values[static_cast<std::size_t>(i)], c < 3 ? m.gyro[c] : m.accel[c - 3]);
    }
  }
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rec.time_s[static_cast<std::size_t>(i)], static_cast<double>(i * kStepUs) * 1e-6);
  }
}

TEST(LcmUserType, ScalarFieldsInDegreesAndGWithNanosecondStamps) {
  LcmUserType t;
  t.definition_path = type_file("usertest_scalar_imu.lcm");
  t.time_field = "timestamp_ns";
  t.time_unit_s = 1e-9;
  t.gyro_fields = {"gx", "gy", "gz"};
  t.accel_fields = {"ax", "ay", "az"};
  t.gyro_scale_to_si = kDegToRad;
  t.accel_scale_to_si = kG;
  const auto message = [](int i) {
    usertest::scalar_imu_t m{};
    // ns beyond 2^53 with sub-µs parts: 499 ns rounds down, 500 ns rounds up.
    m.timestamp_ns = kEpochUs * 1000 + i * kStepUs * 1000 + (i % 2 == 0 ? 499 : 500);
    m.gx = 0.1 + i * 1e-3;
    m.gy = -0.2;
    m.gz = 1.0 / 3.0;
    m.ax = 0.001 * i;
    m.ay = -0.002;
    m.az = -1.0;
    m.temperature = 25.0f;
    m.sequence = i;
    return m;
  };
  const auto path = test::make_temp_dir("lcmuser") / "scalar.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 20; ++i) writer.write("IMU", message(i));
  }
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU", with_user_type(t));
  ASSERT_EQ(rec.sample_count(), 20u);
  for (int i = 0; i < 20; ++i) {
    const usertest::scalar_imu_t m = message(i);
    const auto k = static_cast<std::size_t>(i);
    const double want[6] = {m.gx * kDegToRad, m.gy * kDegToRad, m.gz * kDegToRad,
                            m.ax * kG,        m.ay * kG,        m.az * kG};
    for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(rec.channels[c].values[k], want[c]);
    // Exact µs: i·5000 + (0 for +499 ns, 1 for +500 ns).
    EXPECT_EQ(rec.time_s[k], static_cast<double>(i * kStepUs + i % 2) * 1e-6);
  }
  EXPECT_EQ(rec.channels[0].source_column, "IMU.gx");
  EXPECT_EQ(rec.channels[0].source_unit, shortest_number_text(kDegToRad) + " rad/s");
  EXPECT_EQ(rec.channels[5].source_unit, "9.80665 m/s^2");

  // The exact stamps, through the decoder itself.
  LcmUserImuDecoder decoder(t);
  pipeline::ImuSampleColumns columns = decoder.make_columns();
  std::string error;
  for (int i = 0; i < 2; ++i)
    ASSERT_TRUE(decoder.append(test::lcm_encode(message(i)), false, columns, error));
  EXPECT_EQ(columns.utime_us, (std::vector<std::int64_t>{kEpochUs, kEpochUs + kStepUs + 1}));
}

TEST(LcmUserType, IncrementsWithoutPackageAreDividedByTheSamplePeriod) {
  LcmUserType t;
  t.definition_path = type_file("delta_imu.lcm");
  t.time_field = "t_us";
  t.gyro_fields = {"dtheta"};
  t.accel_fields = {"dvel"};
  t.increments = true;
  const auto message = [](int i) {
    delta_imu_t m{};
    m.t_us = kEpochUs + i * 2'500;  // 400 Hz
    for (int a = 0; a < 3; ++a) {
      m.dtheta[a] = static_cast<float>(1e-5 * (a + 1) + 1e-8 * i);
      m.dvel[a] = static_cast<float>(a == 2 ? -0.0245 : 1e-4 * i);
    }
    return m;
  };
  const auto path = test::make_temp_dir("lcmuser") / "delta.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 30; ++i) writer.write("DELTA", message(i));
  }
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "DELTA", with_user_type(t));
  ASSERT_EQ(rec.sample_count(), 30u);
  ASSERT_NEAR(rec.sample_period_s, 0.0025, 1e-15);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_TRUE(rec.channels[c].from_increments);
    EXPECT_EQ(rec.channels[c].source_unit, c < 3 ? "rad" : "m/s");
    for (int i = 0; i < 30; ++i) {
      const delta_imu_t m = message(i);
      const double increment = c < 3 ? m.dtheta[c] : m.dvel[c - 3];
      EXPECT_EQ(rec.channels[c].values[static_cast<std::size_t>(i)],
                increment / rec.sample_period_s);
    }
  }
}

TEST(LcmUserType, WrongTypeOnTheChannelNamesBothFingerprints) {
  const auto path = test::make_temp_dir("lcmuser") / "ours.lcmlog";
  {
    LogWriter writer(path);
    imunoise::imu_sample_t m{};
    writer.write("INS", m);
  }
  const std::string message = test::error_of(
      [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); });
  EXPECT_THAT(message, HasSubstr(path.string() + ": byte offset 0: wrong type on channel 'INS'"));
  EXPECT_THAT(
      message,
      HasSubstr("expected usertest.ins_t (fingerprint " +
                lcm_fingerprint_text(static_cast<std::uint64_t>(usertest::ins_t::getHash()))));
  EXPECT_THAT(message, HasSubstr("found fingerprint " +
                                 lcm_fingerprint_text(static_cast<std::uint64_t>(
                                     imunoise::imu_sample_t::getHash())) +
                                 " (imunoise.imu_sample_t)"));
}

TEST(LcmUserType, UndecodableMessageAndUnknownChannelAreNamed) {
  const auto path = test::make_temp_dir("lcmuser") / "short.lcmlog";
  {
    LogWriter writer(path);
    writer.write("INS", ins_sample(0));
    const Bytes full = test::lcm_encode(ins_sample(1));
    writer.write_raw("INS", Bytes(full.begin(), full.end() - 3));
  }
  const std::string offset = std::to_string(28 + 3 + test::lcm_encode(ins_sample(0)).size());
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); }),
              HasSubstr(path.string() + ": byte offset " + offset +
                        ": the message does not decode as usertest.ins_t"));
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "IMU", with_user_type(ins_user_type())); }),
              HasSubstr("channel 'IMU' not found; the log holds 'INS' (unknown type"));
}

TEST(LcmUserType, NonFiniteValuesAreAnErrorOrDroppedAndCounted) {
  const auto path = test::make_temp_dir("lcmuser") / "nan.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 10; ++i) {
      usertest::ins_t m = ins_sample(i);
      if (i == 4) m.gyro[1] = std::numeric_limits<double>::quiet_NaN();
      if (i == 6) m.mag[0] = std::numeric_limits<double>::infinity();  // not a used field
      writer.write("INS", m);
    }
  }
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); }),
              HasSubstr("non-finite value in gyro[1] (NaN) (channel 'INS', event number 4)"));
  const pipeline::Recording rec =
      read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type(), true));
  EXPECT_EQ(rec.sample_count(), 9u);
  EXPECT_EQ(rec.report.rows_dropped, 1);
  EXPECT_EQ(rec.report.non_finite_dropped, 1);
}

TEST(LcmUserType, ValueOverflowingWhenScaledIsNonFinite) {
  LcmUserType t;
  t.definition_path = type_file("usertest_scalar_imu.lcm");
  t.time_field = "timestamp_ns";
  t.time_unit_s = 1e-9;
  t.gyro_fields = {"gx", "gy", "gz"};
  t.accel_fields = {"ax", "ay", "az"};
  t.accel_scale_to_si = kG;
  usertest::scalar_imu_t m{};
  m.ax = 1e308;  // finite in g, Inf in m/s²
  LcmUserImuDecoder decoder(t);
  pipeline::ImuSampleColumns columns = decoder.make_columns();
  std::string error;
  EXPECT_FALSE(decoder.append(test::lcm_encode(m), false, columns, error));
  EXPECT_EQ(error, "non-finite value in ax (Inf) after scaling to SI");
  EXPECT_TRUE(decoder.append(test::lcm_encode(m), true, columns, error));
  EXPECT_EQ(columns.size(), 0u);
  EXPECT_EQ(columns.rows_dropped, 1);
}

TEST(LcmUserType, BadMappingsAreInputErrors) {
  const auto with = [](auto change) {
    LcmUserType t = ins_user_type();
    change(t);
    return test::error_of([&] { LcmUserImuDecoder decoder(t); });
  };
  EXPECT_THAT(with([](LcmUserType& t) { t.gyro_fields.clear(); }),
              HasSubstr("no gyro fields given"));
  EXPECT_THAT(with([](LcmUserType& t) { t.accel_fields = {"quat"}; }),
              HasSubstr("accel fields give 4 value(s); x, y, z need 3"));
  EXPECT_THAT(with([](LcmUserType& t) {
                t.gyro_fields = {"gyro[0]", "gyro[1]"};
              }),
              HasSubstr("gyro fields give 2 value(s)"));
  EXPECT_THAT(with([](LcmUserType& t) {
                t.gyro_fields = {"gyro", "mag", "quat"};
              }),
              HasSubstr("gyro field 'gyro' is an array"));
  EXPECT_THAT(with([](LcmUserType& t) { t.accel_fields = {"acc"}; }),
              HasSubstr("field 'acc': struct 'usertest.ins_t' has no member 'acc'; its members: "
                        "utime, device_time, quat[4], gyro[3], accel[3], mag[3], pressure, "
                        "rel_alt"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_field = "stamp"; }), HasSubstr("no member 'stamp'"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_field = "quat"; }),
              HasSubstr("time field 'quat' must be one number"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_unit_s = 0.0; }),
              HasSubstr("time unit 0 s is not a positive number"));
  EXPECT_THAT(with([](LcmUserType& t) { t.gyro_scale_to_si = std::nan(""); }),
              HasSubstr("gyro scale nan is not a finite non-zero factor"));
  EXPECT_THAT(with([](LcmUserType& t) { t.type_name = "ins"; }),
              HasSubstr("no struct 'ins' in the file; it defines: usertest.ins_t"));
  EXPECT_THAT(with([](LcmUserType& t) { t.definition_path = "/nonexistent.lcm"; }),
              HasSubstr("/nonexistent.lcm: cannot open"));
  // The whole read fails the same way, before the log is opened.
  LcmUserType t = ins_user_type();
  t.gyro_fields.clear();
  EXPECT_THAT(
      test::error_of([&] { read_lcm_imu_log("/nonexistent.lcmlog", "INS", with_user_type(t)); }),
      HasSubstr("no gyro fields given"));
}

// --- fuzz regressions (fuzz/fuzz_lcm_type_definition) ---------------------------------------

// A whole fixed-size array in a field path got one slot (and a name string) per element before
// any check: `double g[1000000000]` named whole ran for minutes and exhausted memory.
TEST(LcmTypeFuzzRegression, HugeWholeArrayFieldIsAnInputErrorNotAnAllocation) {
  const LcmTypeFile file =
      parse_lcm_type_definition("struct a { double g[1000000000]; double h[4096]; }", "big.lcm");
  LcmFieldDecoder d(file, 0);
  EXPECT_THAT(test::error_of([&] { d.add_field("g"); }),
              HasSubstr("big.lcm: field 'g': 'g' has 1000000000 elements; a whole array selects "
                        "at most 4096 (name its elements, e.g. g[0])"));
  EXPECT_EQ(d.slot_count(), 0u);
  EXPECT_EQ(d.add_field("g[999999999]").size(), 1u);  // one element is fine
  EXPECT_EQ(d.add_field("h").size(), 4096u);          // the bound itself is allowed
}

// The minimum encoded size of a struct wrapped to 0 for dimensions whose product is 2^64
// ([2^20][2^20][2^24]), so a member of that struct type was skipped as "encodes to nothing" and
// the following members were read from its bytes; the message must fail to decode instead.
TEST(LcmTypeFuzzRegression, DimensionProductBeyond64BitsDoesNotMakeAStructEmpty) {
  const LcmTypeFile file = parse_lcm_type_definition(
      "struct huge_t { int8_t x[1048576][1048576][16777216]; }\n"
      "struct outer_t { huge_t inner; double z; }\n",
      "wrap.lcm");
  LcmFieldDecoder d(file, file.find_struct("outer_t"));
  std::vector<unsigned char> message(16, 0);
  for (int b = 0; b < 8; ++b) {
    message[b] = static_cast<unsigned char>(d.fingerprint() >> (56 - 8 * b));
  }
  std::vector<LcmFieldValue> values;
  std::string error;
  EXPECT_FALSE(d.decode_all(message, values, error));
  EXPECT_THAT(error, HasSubstr("'inner' holds 1 structs of at least"));
}

}  // namespace
}  // namespace imunoise::io
