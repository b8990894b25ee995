/// @file
/// @brief The --gm-convention flag shared by export, discretize and drift: bias instability B
/// as one Gauss–Markov term by a convention of theory.md §4.4 (models/bias_instability_gm.h).
#pragma once

#include <map>
#include <string>

#include "models/bias_instability_gm.h"

namespace imunoise::tools {

/// Command-line names → conventions; the names are models::name_of() of each convention.
inline const std::map<std::string, models::GmConvention>& gm_conventions() {
  static const std::map<std::string, models::GmConvention> map{
      {std::string(models::name_of(models::GmConvention::min_adev_at_tau_min)),
       models::GmConvention::min_adev_at_tau_min},
      {std::string(models::name_of(models::GmConvention::peak_match)),
       models::GmConvention::peak_match},
      {std::string(models::name_of(models::GmConvention::sigma_equals_b)),
       models::GmConvention::sigma_equals_b}};
  return map;
}

}  // namespace imunoise::tools
