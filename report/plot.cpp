#include "report/plot.h"

#include <array>
#include <cstddef>

namespace imunoise::report {

namespace {

constexpr std::array<std::string_view, 8> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000", "#F0E442"};

}  // namespace

std::string_view palette_color(int index) {
  const int n = static_cast<int>(kPalette.size());
  return kPalette[static_cast<std::size_t>(((index % n) + n) % n)];
}

}  // namespace imunoise::report
