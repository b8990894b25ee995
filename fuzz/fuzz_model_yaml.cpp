// libFuzzer target: the YAML loaders on the same text — the native model.yaml
// (io::parse_model_yaml, with the round-trip property: an accepted model, written by
// io::format_model_yaml and parsed again, writes the same text), the simulator's model file
// (io::parse_simulation_model, then the channel models, models::ImuSimulator and one block, as
// `imunoise simulate` runs it) and the input config (io::parse_input_config).
// Only InputError / AnalysisError may escape: the readers throw InputError for any bad text
// (io/noise_model_yaml_reader.cpp, io/simulation_model.cpp, io/input_config.cpp). Any exception
// from format_model_yaml on an accepted model (it throws ContractViolation for a model breaking
// a loading rule) is a finding: the loader let through what the writer refuses.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "io/input_config.h"
#include "io/noise_model_yaml.h"
#include "io/simulation_model.h"
#include "models/noise_simulator.h"

using namespace imunoise;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);

  fuzz::expect_only_typed_errors("model.yaml", [&] {
    const models::NoiseModel model = io::parse_model_yaml(text, "fuzz");
    std::string first;
    try {
      first = io::format_model_yaml(model);
    } catch (const std::exception& e) {
      fuzz::property_failed("format_model_yaml refused a model parse_model_yaml accepted",
                            e.what());
    }
    models::NoiseModel again;
    try {
      again = io::parse_model_yaml(first, "fuzz (written back)");
    } catch (const std::exception& e) {
      fuzz::property_failed("parse_model_yaml refused the text format_model_yaml wrote",
                            std::string(e.what()) + "\n--- text ---\n" + first);
    }
    const std::string second = io::format_model_yaml(again);
    if (second != first) {
      fuzz::property_failed("model.yaml round trip changed the text",
                            "--- first ---\n" + first + "--- second ---\n" + second);
    }
  });

  fuzz::expect_only_typed_errors("simulation model", [&] {
    const io::SimulationModelFile file = io::parse_simulation_model(text, "fuzz");
    // As `imunoise simulate` does with it: channel models, the simulator, a first block.
    models::ImuNoiseModel model;
    for (std::size_t a = 0; a < 3; ++a) {
      (void)io::si_terms_text(file.gyro[a], SensorKind::gyro);
      (void)io::si_terms_text(file.accel[a], SensorKind::accel);
      model.gyro[a] = io::channel_model(file.gyro[a]);
      model.accel[a] = io::channel_model(file.accel[a]);
      models::validate_channel_model(model.gyro[a], "gyro");
      models::validate_channel_model(model.accel[a], "accel");
    }
    models::SimulationOptions options;
    options.sample_rate_hz = file.sample_rate_hz.value_or(100.0);
    options.flicker_band = file.flicker_band.value_or(
        models::FlickerBand{1.0 / options.sample_rate_hz, 2.0 / options.sample_rate_hz});
    models::ImuSimulator simulator(model, options);
    constexpr std::size_t kBlock = 32;
    std::vector<double> values(models::kImuChannels * kBlock);
    std::array<std::span<double>, models::kImuChannels> spans;
    for (std::size_t c = 0; c < models::kImuChannels; ++c) {
      spans[c] = std::span<double>(values).subspan(c * kBlock, kBlock);
    }
    simulator.next_block(spans);
  });

  fuzz::expect_only_typed_errors("input config", [&] {
    const io::InputConfig config = io::parse_input_config(text, "fuzz");
    (void)io::merge_input_configs(io::InputConfig{}, config);
  });
  return 0;
}
