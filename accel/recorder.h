// The recorder protocol: how a walk through a cell-based accelerator reports
// what it does, so that statistics (stats/counters.h) can count any walk
// without accel/ knowing them. A recorder is a template argument of the walk,
// chosen once per frame: a recorder whose methods are empty (NoRecorder)
// compiles away, and so does everything the walk computes only for it.
//
//   cell(index, level, box)   on entering each cell, in the order walked:
//                             its index in the CellLayout (0 .. N_c - 1), its
//                             level (0 for a uniform grid) and `box`, a
//                             callable giving its CellBox, evaluated only if
//                             the recorder calls it
//   test()                    before each triangle test, in the cell last entered
//   hit()                     when that test found a (new closest) hit
//   finish(counts, segment)   once, at the end: the walk's own counts and the
//                             part of the ray it walked
//
// A walk reports every cell it crosses exactly once (tests/accel/walk_test.cpp
// compares the cells reported against the cells the segment crosses).
#pragma once

#include <cstdint>

#include "core/vec3.h"

namespace kappa {

/// How far a walk goes: to the closest hit, to any hit, or along the whole
/// chord (the paper's lines and segments, for statistics).
enum class GridWalk { closest, any, whole };

/// The most levels a cell structure has (grid2's, accel/grid2.h).
inline constexpr int kMaxCellLevels = 4;

/// What one walk did, counted in registers and handed to the recorder once
/// at the end.
struct WalkCounts {
  std::uint64_t cells = 0;  ///< cells visited
  std::uint64_t occupied = 0;  ///< of them, cells holding triangles (the walk reads their lists)
  std::uint64_t refs = 0;   ///< sum of Theta_i over them (before mailboxing)
  std::uint64_t tests = 0;  ///< triangle tests made
  std::uint64_t skips = 0;  ///< tests the mailbox avoided
  /// Sub-grids entered (grid2: steps into refined cells, each a DDA set up
  /// anew); 0 for a structure of one level.
  std::uint64_t descents = 0;
  /// Per level of a structure of several (grid2; the index is the level):
  /// the cells, tests and references of that level's leaves. Zero for a
  /// structure of one level, whose totals above are its level's.
  std::uint64_t level_cells[kMaxCellLevels] = {};
  std::uint64_t level_tests[kMaxCellLevels] = {};
  std::uint64_t level_refs[kMaxCellLevels] = {};
};

/// The part of the ray a walk covered, for the model's prediction of the
/// cells it should cross (eq 24, stats/cost_model.h): the ray o + t d from
/// t_min on, clipped to the cell structure's box as [t_in, t_out], walked up
/// to t_end (the closest hit for closest-hit walks, the ray's tmax
/// otherwise: for an any-hit walk an upper bound). Empty when t_in >= min(t_out, t_end).
struct WalkSegment {
  Vec3d o, d;
  double t_min = 0, t_in = 0, t_out = 0, t_end = 0;
};

/// A cell's box in scene units.
struct CellBox {
  Vec3d lo, hi;
};

/// A recorder that records nothing: every call compiles away.
struct NoRecorder {
  template <class BoxFn>
  void cell(std::uint64_t, int, BoxFn&&) {}
  void test() {}
  void hit() {}
  void finish(const WalkCounts&, const WalkSegment&) {}
};

}  // namespace kappa
