// tinygltf's implementation, compiled here rather than linked from Debian's
// libtinygltf.so (README.Debian offers both), in the configuration of
// tiny_gltf_config.h; it also puts the parser under the fuzzer's
// instrumentation.
#define TINYGLTF_IMPLEMENTATION
#include "renderer/scene/gltf/tiny_gltf_config.h"
