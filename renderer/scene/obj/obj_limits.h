// Limits every scene reader enforces on what it accepts (the OBJ scanner and
// the scene JSON reader alike), kept apart so the lower layer (obj_scan)
// needs nothing of the loader above it.
#pragma once

#include <cstddef>

namespace kappa {

/// Largest coordinate magnitude accepted. The watertight test forms products
/// of three coordinates (T ~ coord^3), which overflow float near 7e12: such
/// files are refused rather than half-rendered.
inline constexpr double kMaxCoordinate = 1e12;

/// Smallest triangle kept, by its longest edge. The watertight test's
/// distance is a product of three coordinates relative to the ray's origin:
/// for a triangle under about 1e-15 across, seen at its own scale, that
/// product underflows single precision (1e-45) and no ray can hit it (measured:
/// a 1e-14 triangle framed by the camera is hit, a 1e-16 one never). Such
/// triangles are left out with a warning that counts them.
inline constexpr double kMinTriangleSize = 1e-15;

/// Most vertices one face may have. tinyobjloader's triangulation takes time
/// growing as the square of a face's vertices (measured here: 10,000 in
/// 0.25 s, 30,000 in 1.7 s, 100,000 in 18 s); a face over the limit is
/// refused with its line, before any is triangulated.
inline constexpr std::size_t kMaxFaceVertices = 16384;

}  // namespace kappa
