// Tests of io/lcm_field_decoder.h: messages the lcm-gen classes of the test types
// (tests/io/lcm_user_types/) encoded decode to exactly their values — every primitive, fixed,
// variable and multi-dimensional arrays, nested structs, selected fields —; bad field paths,
// truncated messages and corrupt lengths or fingerprints are named; corrupted messages never
// crash. Also the fuzz regressions of fuzz/fuzz_lcm_type_definition.
#include "io/lcm_field_decoder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <usertest/arrays_t.hpp>
#include <usertest/primitives_t.hpp>
#include <usertest/sample_t.hpp>
#include <utility>
#include <vector>

#include "io/lcm_type_definition.h"
#include "io/lcm_user_types_test_support.h"
#include "lcm_test_support.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using Bytes = test::LcmBytes;
using namespace lcm_user_types_test;  // the test types, a decoder of one, random messages

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
