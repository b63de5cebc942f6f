// exr_to_png IN.exr OUT.png [EXPOSURE]: an EXR's R, G, B as an 8-bit sRGB
// PNG, for pictures in the documentation (the README's render beside its
// cell map). Values are scaled by 2^EXPOSURE (default 0), clamped to [0, 1]
// and encoded with the sRGB transfer function; no tone mapping beyond that.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/srgb.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/exr_input.h"
#include "renderer/io/png_output.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: exr_to_png IN.exr OUT.png [EXPOSURE]\n");
    return 2;
  }
  try {
    const float scale = argc == 4 ? std::exp2(std::stof(argv[3])) : 1.0f;
    const kappa::ReferenceImage image = kappa::read_reference(argv[1]);
    std::vector<std::uint8_t> rgb(image.rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = kappa::linear_to_srgb_byte(image.rgb[i], scale);
    kappa::AtomicOutput out(argv[2], kappa::OutputKind::image);
    kappa::write_png(out.temp_path(), image.width, image.height, rgb, out.target());
    out.commit();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_to_png: %s\n", e.what());
    return 2;
  }
  return 0;
}
