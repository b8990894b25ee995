#include "analysis/deviation_type.h"

#include <array>
#include <utility>

namespace imunoise::analysis {

namespace {
constexpr std::array<std::pair<DeviationType, std::string_view>, 7> kNames{{
    {DeviationType::adev, "adev"},
    {DeviationType::oadev, "oadev"},
    {DeviationType::mdev, "mdev"},
    {DeviationType::tdev, "tdev"},
    {DeviationType::hdev, "hdev"},
    {DeviationType::ohdev, "ohdev"},
    {DeviationType::totdev, "totdev"},
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
    case DeviationType::oadev:
    case DeviationType::mdev:
    case DeviationType::tdev:
    case DeviationType::ohdev:
      return 4;
  }
  return 4;
}

}  // namespace imunoise::analysis
