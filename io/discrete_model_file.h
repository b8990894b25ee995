/// @file
/// @brief The result files of `imunoise discretize`: discrete_model.yaml and
/// discrete_model.json, one content (Φ, Q_d over a step Δt, with F, G, Q_c and P₀ of the
/// continuous model, the states and noises named with their units, and the white-noise
/// inputs), written and read here. Numbers are written as text that reads back to the same
/// double: the YAML by shortest_number_text (std::to_chars, the shortest such text), the JSON
/// by nlohmann::json (Grisu2: such a text, nearly always the shortest).
#pragma once

#include <string>
#include <vector>

#include "models/state_space.h"
#include "pipeline/sensor_states.h"

namespace imunoise::io {

/// The content of discrete_model.yaml / discrete_model.json.
struct DiscreteModelFile {
  std::string source_model;        ///< path of the model.yaml the states came from
  std::string description;         ///< what the states are (YAML: a header comment)
  std::vector<std::string> notes;  ///< e.g. terms the states leave out (YAML: header comments)
  /// @name The choices made, for people (YAML header comments only; not read back)
  /// @{
  bool conservative = false;  ///< upper interval ends instead of best estimates
  std::string bias_model;     ///< "rw", "gm" or "both"
  std::string gm_convention;  ///< models::name_of() of the B → GM convention
  /// @}
  /// F, G, Q_c, P₀, state_names and noise_names (state_names = discrete.state_names).
  models::ContinuousStateModel continuous;
  /// Φ, Q_d, state_names, dt_s and method (YAML: method in a header comment).
  models::DiscreteStateModel discrete;
  std::vector<pipeline::WhiteNoiseInput> white_noise;
};

/// @name Writing
/// @{
/// discrete_model.yaml: a comment header for people (source, description, method, values,
/// notes, state count), then the keys of the JSON. source_model is a double-quoted scalar
/// (io/yaml_scalar.h: quotes, backslashes and controls escaped), so any path reads back
/// unchanged; the header shows it as is, or quoted the same way when it holds a control
/// character (a comment is one line).
std::string format_discrete_model_yaml(const DiscreteModelFile& file);
/// discrete_model.json (nlohmann::json, indent 2, with a final newline).
std::string format_discrete_model_json(const DiscreteModelFile& file);
/// Writes DIRECTORY/discrete_model.yaml and DIRECTORY/discrete_model.json, each atomically,
/// creating DIRECTORY. Returns DIRECTORY/discrete_model (the path without extension).
/// @throws InputError "DIRECTORY: cannot create the directory: …", or as write_file_atomically.
std::string write_discrete_model(const DiscreteModelFile& file, const std::string& directory);
/// @}

/// @name Reading
/// What each file carries: the YAML reader fills neither description, notes, the choices nor
/// discrete.method (header comments); the JSON reader fills all but the choices. Shapes are
/// checked against the state and noise names (Φ, Q_d, F n×n; G n×p; Q_c p×p; P₀ n).
/// @throws InputError naming SOURCE (and the key) for a syntax error, another format or
///   version, a missing key, a value that is not a finite number, ragged rows or a shape that
///   disagrees with the names.
/// @{
DiscreteModelFile parse_discrete_model_yaml(const std::string& text, const std::string& source);
DiscreteModelFile parse_discrete_model_json(const std::string& text, const std::string& source);
/// Reads PATH: JSON when it ends in ".json", else YAML.
DiscreteModelFile load_discrete_model(const std::string& path);
/// @}

}  // namespace imunoise::io
