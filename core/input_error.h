// Errors in the user's input or options: a one-line message (naming the file
// and line where there is one) that the command line prints, exiting with 2.
// Here, in the lowest library, so that accel/ (a grid over --grid-max-bytes,
// a bad --grid-res), stats/ (a malformed calibration file) and renderer/ all
// throw the same type; anything else that escapes a command is an internal
// error (exit 1).
#pragma once

#include <stdexcept>

namespace kappa {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace kappa
