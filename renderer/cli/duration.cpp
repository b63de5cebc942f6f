#include "renderer/cli/duration.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "core/input_error.h"

namespace kappa {

double parse_duration(const std::string& text, const std::string& option) {
  const auto refuse = [&](const std::string& why) -> double {
    throw InputError(option + ": '" + text + "' " + why);
  };
  double value = 0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto [end, ec] = std::from_chars(first, last, value, std::chars_format::fixed);
  if (ec != std::errc() || end == first) return refuse("is not a duration (a number and a unit: 500ms, 30s, 2m, 1h)");
  const std::string_view unit(end, std::size_t(last - end));
  double scale = 0;
  if (unit == "ms") scale = 1e-3;
  else if (unit == "s") scale = 1;
  else if (unit == "m") scale = 60;
  else if (unit == "h") scale = 3600;
  else if (unit.empty()) return refuse("has no unit (500ms, 30s, 2m or 1h)");
  else return refuse("has an unknown unit (expected ms, s, m or h)");
  const double seconds = value * scale;
  constexpr double kYear = 365.0 * 24 * 3600;
  if (!(seconds > 0) || !std::isfinite(seconds) || seconds > kYear)
    return refuse("is not a duration above 0 and at most a year");
  return seconds;
}

}  // namespace kappa
