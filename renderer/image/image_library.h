// What Kappa asks of OpenImageIO, behind an interface that names none of its
// types: texture lookups through its TextureSystem (mip-mapped, tiled,
// cached), whole images read at load (environment maps, cut-out masks) and
// 8-bit previews written. OpenImageIO itself lives in a module of its own
// (libkappa_oiio.so, oiio_module.cpp) that image_library() loads on first
// use: Debian's OpenImageIO links about 260 shared libraries, whose loading
// took 0.45 s of every `kappa` start, and an untextured render never pays it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kappa {

/// An image file's header: what a texture or environment needs to know
/// before it reads a texel.
struct ImageFacts {
  int width = 0, height = 0, channels = 0;
  bool alpha = false;     ///< it has an alpha channel (its index is alpha_channel)
  int alpha_channel = -1;
  bool floating = false;  ///< stored as half or float (linear data in Blender's view)
  std::string format;     ///< OpenImageIO's format name ("png", "openexr", "hdr", ...)
};

/// Per-channel summary of an image's top level, read at load to warn about
/// texels a renderer cannot use.
struct TexelScan {
  std::uint64_t nan = 0, infinite = 0, negative = 0;
};

/// How a lookup outside [0, 1] wraps, per axis (MTL -clamp on: clamp, else
/// periodic; glTF's sampler: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT).
enum class TextureWrap : unsigned char { periodic, clamp, mirror };
/// nearest: the texel the coordinates fall in, finest level (tests, cut-outs);
/// filtered: bilinear within trilinear/anisotropic MIP levels chosen from the
/// footprint (OpenImageIO's defaults for a renderer's lookups).
enum class TextureFilter { nearest, filtered };

/// A texture lookup's coordinates and footprint: (s, t) with t = 0 at the
/// image's top row (OpenImageIO's convention; an OBJ's v runs up, so the
/// caller passes 1 - v), derivatives zero for a point lookup.
struct TextureCoords {
  float s = 0, t = 0;
  float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
};

/// The TextureSystem's own counters for the report.
struct TextureCacheStats {
  std::uint64_t lookups = 0;        ///< texture() calls
  std::uint64_t tile_lookups = 0;   ///< find_tile calls (each texel block the filters asked for)
  std::uint64_t tiles_read = 0;     ///< tiles read from files (misses)
  std::uint64_t bytes_read = 0;
  std::uint64_t cache_bytes = 0;    ///< memory the cache holds
  std::uint64_t cache_limit_bytes = 0;
  std::uint64_t files = 0;
  double file_io_s = 0;
};

class ImageLibrary {
 public:
  virtual ~ImageLibrary() = default;

  /// Makes `name` an image file whose bytes are `bytes` (an image a glTF
  /// file holds in a buffer or a data URI): every call below then reads it
  /// from memory. Names are the caller's to keep unique; a second call with
  /// a name does nothing.
  virtual void add_memory_file(const std::string& name, std::vector<unsigned char> bytes) = 0;

  /// The header of `path`; throws std::runtime_error with OpenImageIO's
  /// words when it cannot be opened or is not an image it reads.
  virtual ImageFacts inspect(const std::string& path) = 0;
  /// The top level of `path` as floats, `channels` per texel (the file's
  /// first ones; missing ones 0, an alpha asked for but absent 1), row 0 at
  /// the top. Throws std::runtime_error for a truncated or corrupt file.
  virtual std::vector<float> read(const std::string& path, int channels) = 0;
  /// Counts the texels of `path` that are NaN, infinite or negative (reads it).
  virtual TexelScan scan(const std::string& path) = 0;

  /// A handle for lookups of `path` (opened lazily by the cache).
  virtual void* texture(const std::string& path) = 0;
  /// `count` channels from `first` at `at`, into out[0..count). False when
  /// the lookup failed (out is then 0). Thread-safe; allocates nothing in
  /// the steady state (OpenImageIO's per-thread data is reused).
  virtual bool lookup(void* texture, TextureWrap wrap_s, TextureWrap wrap_t, TextureFilter filter, int first, int count,
                      const TextureCoords& at, float* out) = 0;
  virtual TextureCacheStats statistics() = 0;

  /// 8-bit pixels (`channels` per pixel, row 0 at the top) encoded as the
  /// file format `extension` names (".png", ".jpg", ".tif"), in memory: the
  /// caller writes the bytes wherever the output leads (a temporary, a
  /// device, a descriptor). Throws std::runtime_error on failure.
  virtual std::vector<std::uint8_t> encode_8bit(const std::string& extension, int width, int height, int channels,
                                                const std::vector<std::uint8_t>& pixels) = 0;

  /// Writes 8-bit pixels (`channels` per pixel, row 0 at the top) to `path`
  /// in the format its extension names, directly (the caller made `path` a
  /// temporary beside the target). Throws std::runtime_error on failure.
  virtual void write_8bit(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& pixels) = 0;
};

/// The library, its module loaded on the first call (thread-safe). Throws
/// InputError naming the module when it cannot be loaded.
ImageLibrary& image_library();
/// Whether this process has loaded the module (what tests and the report read).
bool image_library_loaded();

}  // namespace kappa

/// The module's one entry point (oiio_module.cpp): a new library with a
/// texture cache of `cache_mb` megabytes.
extern "C" kappa::ImageLibrary* kappa_image_library_create(int cache_mb);
