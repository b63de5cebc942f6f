// libFuzzer target: the reference-image reader of `kappa converge --reference`
// (Kappa's header walk, OpenEXR, then Kappa's channel and value checks). An image it accepts
// must hold width x height finite, non-negative RGB (and variance) values.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/check.h"
#include "core/error.h"
#include "fuzz_support.h"
#include "renderer/io/exr_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  const auto path = fuzz::write_scratch("reference.exr", data, size);
  try {
    // 1 GiB: what it reads then stays below libFuzzer's 4 GiB limit on one
    // allocation, OpenEXR's per-thread decoding buffers included.
    const ReferenceImage image = read_reference(path, std::nullopt, std::uint64_t(1) << 30);
    KAPPA_CHECK(image.width > 0 && image.height > 0);
    const std::size_t values = 3 * std::size_t(image.width) * std::size_t(image.height);
    KAPPA_CHECK_EQ(image.rgb.size(), values);
    KAPPA_CHECK(image.variance.empty() || image.variance.size() == values);
    for (const float v : image.rgb) KAPPA_CHECK(std::isfinite(v) && v >= 0);
    for (const float v : image.variance) KAPPA_CHECK(std::isfinite(v) && v >= 0);
  } catch (const InputError& e) {
    fuzz::require_refusal_names_an_input(e.what());
  }
  return 0;
}
