// Limits every scene reader enforces on what it accepts (the OBJ scanner and
// the scene JSON reader alike), kept apart so the lower layer (obj_scan)
// needs nothing of the loader above it.
#pragma once

namespace kappa {

/// Largest coordinate magnitude accepted. The watertight test forms products
/// of three coordinates (T ~ coord^3), which overflow float near 7e12: such
/// files are refused rather than half-rendered.
inline constexpr double kMaxCoordinate = 1e12;

}  // namespace kappa
