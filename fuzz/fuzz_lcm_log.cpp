// libFuzzer target: the bytes as an lcm-logger file through io::list_lcm_log_channels and
// io::read_lcm_imu_log (io/lcm_log.h), on the first channels of the log, as imu_sample_t and
// as two users' types (io/lcm_type_definition.h: fixed-size increments and nested structs with
// variable arrays). Only InputError / AnalysisError may escape.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/lcm_log.h"

using namespace imunoise;

namespace {

// tests/io/lcm_user_types/delta_imu.lcm and usertest_nested.lcm.
constexpr const char* kDeltaImu = R"(struct delta_imu_t
{
    int64_t t_us;
    float dtheta[3];
    float dvel[3];
}
)";
constexpr const char* kNested = R"(package usertest;
struct vec3_t { double v[3]; }
struct sample_t
{
    int64_t utime;
    vec3_t gyro;
    usertest.vec3_t accel;
    int32_t n_history;
    vec3_t history[n_history];
    status_t status;
    vec3_t pair[2];
    string frame;
}
struct status_t
{
    int8_t n_codes;
    int16_t codes[n_codes];
    boolean ok;
}
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile log("log.lcmlog");
  static fuzz::ScratchFile delta_def("delta_imu.lcm");
  static fuzz::ScratchFile nested_def("usertest_nested.lcm");
  static const bool defs_written = (delta_def.write(kDeltaImu), nested_def.write(kNested), true);
  (void)defs_written;

  const std::string& path = log.write(data, size);
  std::vector<io::LcmLogChannel> channels;
  fuzz::expect_only_typed_errors("list_lcm_log_channels",
                                 [&] { channels = io::list_lcm_log_channels(path); });
  (void)io::describe_lcm_log_channels(channels);

  io::LcmUserType delta;
  delta.definition_path = delta_def.path();
  delta.time_field = "t_us";
  delta.gyro_fields = {"dtheta"};
  delta.accel_fields = {"dvel"};
  delta.increments = true;
  io::LcmUserType nested;
  nested.definition_path = nested_def.path();
  nested.type_name = "usertest.sample_t";
  nested.time_field = "utime";
  nested.time_unit_s = 1e-9;
  nested.gyro_fields = {"gyro.v"};
  nested.accel_fields = {"accel.v[0]", "accel.v[1]", "history[1].v[2]"};
  nested.gyro_scale_to_si = 0.017453292519943295;

  // A channel that is not in the log must be an InputError too.
  if (channels.empty()) channels.push_back({"IMU", 0, std::nullopt, "", 0});
  for (std::size_t i = 0; i < channels.size() && i < 3; ++i) {
    const std::string& name = channels[i].name;
    for (int variant = 0; variant < 4; ++variant) {
      io::LcmReadOptions options;
      options.drop_non_finite = (variant & 1) != 0;
      if (variant == 2) options.user_type = delta;
      if (variant == 3) options.user_type = nested;
      fuzz::expect_only_typed_errors("read_lcm_imu_log",
                                     [&] { (void)io::read_lcm_imu_log(path, name, options); });
    }
  }
  return 0;
}
