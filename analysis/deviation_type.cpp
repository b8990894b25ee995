#include "analysis/deviation_type.h"

#include <array>
#include <utility>

namespace imunoise::analysis {

namespace {
constexpr std::array<std::pair<DeviationType, std::string_view>, 11> kNames{{
    {DeviationType::adev, "adev"},
    {DeviationType::oadev, "oadev"},
    {DeviationType::mdev, "mdev"},
    {DeviationType::tdev, "tdev"},
    {DeviationType::hdev, "hdev"},
    {DeviationType::ohdev, "ohdev"},
    {DeviationType::totdev, "totdev"},
    {DeviationType::mtotdev, "mtotdev"},
    {DeviationType::ttotdev, "ttotdev"},
    {DeviationType::htotdev, "htotdev"},
    {DeviationType::theo1, "theo1"},
}};
}  // namespace

std::string_view to_string(DeviationType type) {
  for (const auto& [t, name] : kNames) {
    if (t == type) return name;
  }
  return "unknown";
}

std::optional<DeviationType> parse_deviation_type(std::string_view name) {
  for (const auto& [t, n] : kNames) {
    if (n == name) return t;
  }
  return std::nullopt;
}

int stop_ratio(DeviationType type) {
  switch (type) {
    case DeviationType::adev:
    case DeviationType::hdev:
      return 5;
    case DeviationType::totdev:
      return 2;
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
    case DeviationType::htotdev:
      return 3;
    case DeviationType::theo1:
      return 1;
    case DeviationType::oadev:
    case DeviationType::mdev:
    case DeviationType::tdev:
    case DeviationType::ohdev:
      return 4;
  }
  return 4;
}

bool cost_grows_with_m(DeviationType type) {
  return type == DeviationType::mtotdev || type == DeviationType::ttotdev ||
         type == DeviationType::htotdev || type == DeviationType::theo1;
}

double tau_of(DeviationType type, std::int64_t m, double tau0_s) {
  const double tau = static_cast<double>(m) * tau0_s;
  return type == DeviationType::theo1 ? 0.75 * tau : tau;
}

}  // namespace imunoise::analysis
