// libFuzzer target: the OBJ reader (scan_obj's checks, then tinyobjloader on
// the sanitized text), through load_scene as `kappa render x.obj` reaches it.
// Anything but a scene that holds the renderer's assumptions or an InputError
// of one line naming the file is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  const auto path = fuzz::write_scratch("fuzz.obj", data, size);
  fuzz::load_and_check(path);
  return 0;
}
