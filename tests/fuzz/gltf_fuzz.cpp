// libFuzzer target: the glTF reader (Kappa's container, nesting and URI
// checks, tinygltf's parser compiled in with them, then the accessor, node,
// material, camera and light checks), through load_scene as `kappa render
// model.gltf` calls it. An input starting with the GLB magic is read as a
// binary glTF whatever its name says. The scratch folder holds links to the
// buffers and images of assets/gltf/, so a fuzzed file can name them (the
// seeds do).
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_support.h"

namespace {

void link_gltf_resources() {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(KAPPA_SOURCE_DIR) / "assets" / "gltf", ec)) {
    const auto ext = entry.path().extension();
    if (!entry.is_regular_file() || (ext != ".bin" && ext != ".png")) continue;
    fs::create_symlink(entry.path(), kappa::fuzz::scratch_dir() / entry.path().filename(), ec);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  static const bool linked = (link_gltf_resources(), true);
  (void)linked;
  const auto path = fuzz::write_scratch("model.gltf", data, size);
  fuzz::load_and_check(path);
  return 0;
}
