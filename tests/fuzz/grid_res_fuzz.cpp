// libFuzzer target: the accelerator flags as every command parses them
// (--grid-res, --grid-density, --grid-max-bytes through CLI11 and Kappa's
// validators). The input is split at newlines into up to three values. A
// value accepted must be one the grid can use: 1 ... kMaxGridAxis cells per
// axis, and a --grid-res that prints and parses back to itself.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/grid_resolution.h"
#include "core/check.h"
#include "core/error.h"
#include "renderer/cli/accel_flags.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> values;
  std::size_t start = 0;
  while (values.size() < 3) {
    const std::size_t end = text.find('\n', start);
    values.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }

  // The parser alone.
  try {
    if (const auto res = parse_grid_resolution(values[0])) {
      for (int axis = 0; axis < 3; ++axis) KAPPA_CHECK((*res)[axis] >= 1 && (*res)[axis] <= kMaxGridAxis);
      const auto again = parse_grid_resolution(res->to_string());
      KAPPA_CHECK(again.has_value() && *again == *res);
    }
  } catch (const InputError& e) {
    KAPPA_CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }

  // The flags, as a command line gives them.
  static const char* const kFlags[] = {"--grid-res", "--grid-density", "--grid-max-bytes"};
  CLI::App app("fuzz");
  AccelOptions options;
  add_grid_flags(app, options);
  std::vector<std::string> args;  // CLI11 takes them last to first
  for (std::size_t i = values.size(); i-- > 0;) {
    args.push_back(values[i]);
    args.push_back(kFlags[i]);
  }
  try {
    app.parse(args);
  } catch (const CLI::ParseError&) {
    return 0;
  }
  const auto res = parse_grid_resolution(options.grid_res);  // accepted by the flag: must not throw now
  if (res) KAPPA_CHECK(res->cells() >= 1);
  KAPPA_CHECK(std::isfinite(options.grid_density) && options.grid_density >= 0);
  KAPPA_CHECK(options.max_bytes() > 0);
  return 0;
}
