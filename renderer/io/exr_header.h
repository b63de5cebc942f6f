// A check of an OpenEXR file's header before OpenEXR reads it. OpenEXR 3.1
// allocates and fills an attribute's declared size before comparing it with
// the file: a 1 kB file can declare a 2 GB string attribute (found by the
// exr_reference fuzz target: 10 s and 2 GB for one input).
#pragma once

#include <filesystem>

namespace kappa {

/// Walks the header(s) of the OpenEXR file at `path` as OpenEXR 3.1 reads
/// them -- attribute name, type, size, then the value as that type's reader
/// consumes it (a fixed size for most types, whatever the declared one; a
/// channel list up to its empty name; a preview's width x height pixels; a
/// string vector's strings; the declared size for the rest), up to the null
/// byte that ends a header (every header of a multi-part file) -- and throws
/// InputError naming the file when any of it would read past the file's end
/// or a name or type runs past the longest OpenEXR allows, or the file does
/// not start with OpenEXR's magic number.
void check_exr_header(const std::filesystem::path& path);

}  // namespace kappa
