// Durations on the command line (--time-budget): a number and its unit,
// never a bare number, whose unit a reader would have to guess.
#pragma once

#include <string>

namespace kappa {

/// Seconds in "500ms", "30s", "2m", "1h" or "1.5s". Throws InputError
/// naming `option` for a bare number, another unit, or a duration that is
/// not positive, finite and at most a year.
double parse_duration(const std::string& text, const std::string& option);

}  // namespace kappa
