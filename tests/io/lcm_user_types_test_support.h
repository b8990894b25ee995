/// @file
/// @brief Test helpers of the users' LCM type tests (tests/io/lcm_type_definition_test.cpp,
/// lcm_fingerprint_test.cpp, lcm_field_decoder_test.cpp, lcm_user_imu_decoder_test.cpp): the
/// test types of tests/io/lcm_user_types/ (also compiled by lcm-gen, tests/CMakeLists.txt), a
/// decoder of one of them, and random messages of the generated classes (fixed seed).
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <usertest/sample_t.hpp>
#include <usertest/vec3_t.hpp>
#include <utility>

#include "io/lcm_field_decoder.h"
#include "io/lcm_type_definition.h"

namespace imunoise::io::lcm_user_types_test {

/// The path of the test type file NAME (tests/io/lcm_user_types/).
inline std::string type_file(const std::string& name) {
  return std::string(IMUNOISE_SOURCE_DIR) + "/tests/io/lcm_user_types/" + name;
}

/// A decoder of the struct TYPE of the test type file FILE.
inline LcmFieldDecoder decoder_for(const std::string& file, const std::string& type) {
  LcmTypeFile parsed = read_lcm_type_definition(type_file(file));
  const std::size_t index = parsed.find_struct(type);
  return LcmFieldDecoder(std::move(parsed), index);
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

inline usertest::vec3_t random_vec3(Random& r) {
  usertest::vec3_t v{};
  for (double& x : v.v) x = r.real();
  return v;
}

inline usertest::sample_t random_sample(Random& r) {
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

}  // namespace imunoise::io::lcm_user_types_test
