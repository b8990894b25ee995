#include "io/duration_parser.h"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>

#include "common/errors.h"
#include "common/units.h"

namespace imunoise::io {

double parse_duration_s(const std::string& text, const std::string& what, bool allow_zero) {
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
    std::string message = what;
    message.append(": expected a ")
        .append(allow_zero ? "non-negative" : "positive")
        .append(" number with unit s, min or h (e.g. 2h, 30min, 600s), got '")
        .append(text)
        .append("'");
    // The usual slips, with the spelling that works.
    std::string_view u = unit;
    while (!u.empty() && u.front() == ' ') u.remove_prefix(1);
    if (ec == std::errc() && !unit.empty() && unit.front() == ' ') {
      message.append(" (write the unit without a space, e.g. 30min)");
    } else if (u == "m" || u == "mins" || u == "minute" || u == "minutes") {
      message.append(" (use 'min' for minutes)");
    } else if (u == "sec" || u == "secs" || u == "second" || u == "seconds") {
      message.append(" (use 's' for seconds)");
    } else if (u == "hr" || u == "hrs" || u == "hour" || u == "hours") {
      message.append(" (use 'h' for hours)");
    } else if (u == "ms") {
      message.append(" (the smallest unit is s: write e.g. 0.5s)");
    }
    throw InputError(message);
  }
  return value * scale;
}

}  // namespace imunoise::io
