// Tests of io/lcm_fingerprint.h: the fingerprint of a user's LCM type computed at run time
// equals lcm-gen's getHash() for every test type of tests/io/lcm_user_types/ (also compiled by
// lcm-gen, tests/CMakeLists.txt) and for imunoise's own imu_sample_t, and heads every encoded
// message.
#include "io/lcm_fingerprint.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <delta_imu_t.hpp>
#include <imunoise/imu_sample_t.hpp>
#include <string>
#include <usertest/arrays_t.hpp>
#include <usertest/ins_t.hpp>
#include <usertest/primitives_t.hpp>
#include <usertest/sample_t.hpp>
#include <usertest/scalar_imu_t.hpp>
#include <usertest/status_t.hpp>
#include <usertest/vec3_t.hpp>

#include "io/lcm_field_decoder.h"
#include "io/lcm_type_definition.h"
#include "io/lcm_user_types_test_support.h"
#include "lcm_test_support.h"

namespace imunoise::io {
namespace {

using Bytes = test::LcmBytes;
using namespace lcm_user_types_test;  // the test types, a decoder of one, random messages

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

}  // namespace
}  // namespace imunoise::io
