#include "renderer/io/png_output.h"

#include <png.h>

#include <cerrno>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace kappa {

void write_png(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb,
               const std::filesystem::path& shown) {
  KAPPA_CHECK_EQ(rgb.size(), 3 * std::size_t(width) * std::size_t(height));
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGB;
  errno = 0;
  // libpng's simplified API: no setjmp here; a failure is its return value
  // and message (and errno for the system's reason).
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), png_int_32(3 * width), nullptr)) {
    const int err = errno;
    const std::string why = image.message;
    png_image_free(&image);
    fail_output(shown.empty() ? path : shown, "cannot write PNG (" + why + ")", err);
  }
}

}  // namespace kappa
