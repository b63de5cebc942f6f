// exr_compare A.exr B.exr: whether two EXR images hold bit for bit the same
// pixels in every channel (their headers, which carry dates and hashes, are
// not compared). Prints "same" and exits 0, or, per channel that differs, the
// number of differing pixels and the largest difference, and exits 1; exit 2
// when the images cannot be compared (unreadable, other sizes or channels).
// What the issues' "images bitwise before and after" claims are checked with.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

namespace {

struct Image {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;
};

Image read(const char* path) {
  Imf::InputFile file(path);
  const Imath::Box2i dw = file.header().dataWindow();
  Image image;
  image.width = dw.max.x - dw.min.x + 1;
  image.height = dw.max.y - dw.min.y + 1;
  Imf::FrameBuffer fb;
  const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    std::vector<float>& v = image.channels[it.name()];
    v.assign(n, 0.0f);
    char* base = reinterpret_cast<char*>(v.data()) -
                 (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * image.width) * std::ptrdiff_t(sizeof(float));
    fb.insert(it.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(image.width)));
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: exr_compare A.exr B.exr\n");
    return 2;
  }
  try {
    const Image a = read(argv[1]), b = read(argv[2]);
    if (a.width != b.width || a.height != b.height) {
      std::printf("sizes differ: %dx%d and %dx%d\n", a.width, a.height, b.width, b.height);
      return 2;
    }
    bool same = a.channels.size() == b.channels.size();
    for (const auto& [name, va] : a.channels) {
      const auto it = b.channels.find(name);
      if (it == b.channels.end()) {
        std::printf("channel %s only in %s\n", name.c_str(), argv[1]);
        return 2;
      }
      std::size_t differ = 0;
      double largest = 0;
      for (std::size_t i = 0; i < va.size(); ++i)
        if (std::memcmp(&va[i], &it->second[i], sizeof(float)) != 0) {
          ++differ;
          largest = std::max(largest, std::abs(double(va[i]) - double(it->second[i])));
        }
      if (differ > 0) {
        same = false;
        std::printf("channel %s: %zu of %zu pixels differ, largest difference %g\n", name.c_str(), differ, va.size(),
                    largest);
      }
    }
    if (same) std::printf("same\n");
    return same ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_compare: %s\n", e.what());
    return 2;
  }
}
