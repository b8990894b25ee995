/// @file
/// @brief The --gm-convention flag shared by export, discretize and drift: bias instability B
/// as one Gauss–Markov term by a convention of theory.md §4.4 (models/bias_instability_gm.h).
#pragma once

#include <map>
#include <string>

#include "models/bias_instability_gm.h"

namespace imunoise::tools {

/// Command-line names → conventions (models::gm_conventions_by_name).
inline const std::map<std::string, models::GmConvention, std::less<>>& gm_conventions() {
  return models::gm_conventions_by_name();
}

}  // namespace imunoise::tools
