// tinygltf as Kappa builds it (tinygltf_build.cpp): every file that includes
// it must see the same configuration, which changes the classes' defaults.
// Without stb_image (images are decoded through OpenImageIO), without its
// file system (gltf_file.cpp serves every file after its own checks) and
// without reading external images (OpenImageIO opens them by name).
#pragma once

#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif
#ifndef TINYGLTF_NO_FS
#define TINYGLTF_NO_FS
#endif
#include <fstream>  // its writer names std::ofstream even without its file system

#include <tiny_gltf.h>
