#include "renderer/image/image_library.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <system_error>

#include "core/input_error.h"

namespace kappa {
namespace {

/// The texture cache's size: OpenImageIO's default (1 GiB) would hold all of a
/// textured Sponza several times; 256 MiB keeps a frame's working set and
/// leaves the memory to the accelerators.
constexpr int kTextureCacheMb = 256;

std::atomic<bool> g_loaded{false};

/// Where the module is: beside the executable (build/kappa and
/// build/libkappa_oiio.so), else in the build tree it was built in (tests).
std::filesystem::path module_path() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path beside = exe.parent_path() / "libkappa_oiio.so";
    if (std::filesystem::exists(beside, ec)) return beside;
  }
  return std::filesystem::path(KAPPA_MODULE_DIR) / "libkappa_oiio.so";
}

ImageLibrary* load() {
  const std::filesystem::path path = module_path();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw InputError("cannot load the OpenImageIO module " + path.string() + " (" + (why ? why : "unknown") +
                     "): textures, environment images and PNG previews need it (tools/setup.sh installs OpenImageIO, "
                     "tools/build.sh builds the module)");
  }
  using Create = ImageLibrary* (*)(int);
  auto create = reinterpret_cast<Create>(dlsym(handle, "kappa_image_library_create"));
  if (!create) throw InputError("the OpenImageIO module " + path.string() + " has no kappa_image_library_create");
  g_loaded = true;
  // Never closed: the library lives as long as the process (dlclose with
  // OpenImageIO's threads and static objects alive is undefined).
  return create(kTextureCacheMb);
}

}  // namespace

ImageLibrary& image_library() {
  static ImageLibrary* const library = load();  // thread-safe; a throw leaves it to be tried again
  return *library;
}

bool image_library_loaded() { return g_loaded; }

}  // namespace kappa
