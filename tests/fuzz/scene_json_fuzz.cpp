// libFuzzer target: the scene JSON reader (nlohmann-json, then Kappa's key,
// number, camera, film and mesh checks). The scratch folder holds links to the
// OBJ and MTL files of assets/, so a fuzzed scene can name real meshes (the
// seeds' scene.json files do).
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_support.h"

namespace {

void link_asset_meshes() {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(KAPPA_SOURCE_DIR) / "assets", ec)) {
    const auto ext = entry.path().extension();
    if (!entry.is_regular_file() || (ext != ".obj" && ext != ".mtl")) continue;
    fs::create_symlink(entry.path(), kappa::fuzz::scratch_dir() / entry.path().filename(), ec);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  static const bool linked = (link_asset_meshes(), true);
  (void)linked;
  const auto path = fuzz::write_scratch("scene.json", data, size);
  fuzz::load_and_check(path);
  return 0;
}
