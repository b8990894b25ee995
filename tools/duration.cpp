#include "tools/duration.h"

#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

#include "common/errors.h"
#include "common/units.h"

namespace imunoise::tools {

double parse_duration_s(const std::string& text, const std::string& flag, bool allow_zero) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  const std::string_view unit(ptr, static_cast<std::size_t>(end - ptr));
  double scale = 0.0;
  if (unit.empty() || unit == "s") {
    scale = 1.0;
  } else if (unit == "min") {
    scale = 60.0;
  } else if (unit == "h") {
    scale = units::kHour;
  }
  const bool in_range = allow_zero ? value >= 0.0 : value > 0.0;
  if (ec != std::errc() || scale == 0.0 || !std::isfinite(value) || !in_range) {
    throw InputError(flag + ": expected a " + (allow_zero ? "non-negative" : "positive") +
                     " number with unit s, min or h (e.g. 2h, 30min, 600s), got '" + text + "'");
  }
  return value * scale;
}

}  // namespace imunoise::tools
