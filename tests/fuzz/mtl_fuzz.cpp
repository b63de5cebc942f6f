// libFuzzer target: the MTL reader (scan_mtl, then tinyobjloader's material
// parser and Kappa's conversion to materials), reached from a fixed OBJ that
// names the fuzzed library and uses three of its likely material names.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kappa;
  static const std::string obj =
      "mtllib fuzz.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "usemtl light\nf 1 2 3\n"
      "usemtl white\nf 2 4 3\n"
      "usemtl a\nf 1 2 4\n";
  fuzz::write_scratch("fuzz.mtl", data, size);  // the library the fixed OBJ names
  const auto path =
      fuzz::write_scratch("fuzz_mtl.obj", reinterpret_cast<const std::uint8_t*>(obj.data()), obj.size());
  fuzz::load_and_check(path);
  return 0;
}
