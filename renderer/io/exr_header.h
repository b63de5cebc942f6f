// A check of an OpenEXR file's header before OpenEXR reads it. OpenEXR 3.1
// allocates and fills an attribute's declared size before comparing it with
// the file: a 1 kB file can declare a 2 GB string attribute (found by the
// exr_reference fuzz target: 10 s and 2 GB for one input).
#pragma once

#include <cstdint>
#include <filesystem>

namespace kappa {

/// What the first header declares of the pixels OpenEXR will decode.
struct ExrLayout {
  std::int64_t width = 0, height = 0;  ///< the data window's; 0 when the header has none
  int channels = 0;
  std::uint64_t pixel_bytes = 0;    ///< the channels' bytes a pixel: 2 for HALF, 4 for UINT and FLOAT
  int compression = 0;              ///< OpenEXR's code: 0 none, 1 RLE, 2 ZIPS, 3 ZIP, 4 PIZ, ... 9 DWAB
  std::int64_t tile_width = 0, tile_height = 0;  ///< 0 for a scanline file

  /// Bytes of one chunk OpenEXR decodes at a time, all channels: the
  /// scanlines its compression packs together (1 to 256), or for a tiled file
  /// a row of tiles (what its scanline reader caches); in double since a
  /// header can declare a window of 2^32 x 2^32.
  double chunk_bytes() const;
};

/// Walks the header(s) of the OpenEXR file at `path` as OpenEXR 3.1 reads
/// them -- attribute name, type, size, then the value as that type's reader
/// consumes it (a fixed size for most types, whatever the declared one; a
/// channel list up to its empty name; a preview's width x height pixels; a
/// string vector's strings; the declared size for the rest), up to the null
/// byte that ends a header (every header of a multi-part file) -- and throws
/// InputError naming the file when any of it would read past the file's end
/// or a name or type runs past the longest OpenEXR allows, or the file does
/// not start with OpenEXR's magic number. Returns the first header's layout,
/// from which a reader can refuse an image before OpenEXR's open allocates its
/// decoding buffers (a few GB for a 1 kB file declaring 5373955 x 3 pixels).
ExrLayout check_exr_header(const std::filesystem::path& path);

}  // namespace kappa
