// Counters for one class of rays walked through a cell-based accelerator:
// per cell (visits -> p_i) and in total. A CellCounters gives the recorders
// of the walks' protocol (accel/recorder.h): one per thread, merged once at
// the end. Totals are counted by the walk in registers and added once per
// ray; per-cell visits are added per cell, into the thread's own arrays or,
// for sampled paths, into arrays all threads share.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/recorder.h"
#include "core/vec3.h"
#include "cost_model.h"
#include "recent_cells.h"
#include "split_counts.h"

namespace kappa {

/// Totals over all rays of a class (64-bit: renders cast billions).
struct ClassTotals {
  std::uint64_t rays = 0;
  std::uint64_t cells = 0;          ///< cells visited, summed over rays
  std::uint64_t occupied_cells = 0; ///< of them, cells holding triangles
  std::uint64_t tests = 0;          ///< triangle tests performed (after mailboxing)
  std::uint64_t mailbox_skips = 0;  ///< tests avoided by the mailbox
  std::uint64_t refs = 0;           ///< sum of Theta_i over visited cells (before mailboxing)
  std::uint64_t hits = 0;           ///< rays that hit something
  /// Cut-out (alpha) tests: opacity looked up at a candidate hit; each is
  /// counted in `tests` too, as it is part of testing the triangle.
  std::uint64_t alpha_tests = 0;
  /// Per level of a structure of several (grid2): cells, tests, references (WalkCounts).
  std::uint64_t level_cells[kMaxCellLevels] = {};
  std::uint64_t level_tests[kMaxCellLevels] = {};
  std::uint64_t level_refs[kMaxCellLevels] = {};
  /// Sum over rays of the model's predicted cells (WalkCounts) in 1/1024
  /// units: an integer, so totals do not depend on how threads split rays.
  std::uint64_t predicted_fixed = 0;
  /// Coherence (stats/recent_cells.h), counted by the render's counting
  /// frames only (zero elsewhere): cell steps into cells the tile's recent
  /// walks had not entered, and the triangle tests made in them.
  std::uint64_t cold_cells = 0;
  std::uint64_t cold_tests = 0;
  /// Sub-grids entered (grid2; WalkCounts::descents).
  std::uint64_t descents = 0;

  double predicted_cells() const { return double(predicted_fixed) / 1024.0; }

  ClassTotals& operator+=(const ClassTotals& o);
};

/// Per-cell counts of one class of rays: the rays that visited each cell
/// (-> p_i). Per-cell triangle tests and hits were counted once and read by
/// nothing; the totals keep them.
struct CellArrays {
  static constexpr std::size_t kBytesPerCell = SplitCounts::kBytesPerCount;
  explicit CellArrays(std::size_t cells) : visits(cells) {}
  SplitCounts visits;
};

/// How a walk counts per cell: not at all (totals only), into its thread's
/// own arrays, or into arrays every thread shares. Shared arrays take atomic
/// increments: right for sampled paths, which write rarely, as one copy then
/// serves every thread (no per-thread memory, no merge); wrong for counting
/// every path, where threads would fight over the same cache lines.
enum class PerCell { no, own, shared };

class CellCounters {
 public:
  /// Counters for `cells` cells of size `cell_size` (the uniform size eq 24
  /// predicts with; zero for cells of differing sizes, which predicts 0),
  /// with per-cell arrays of their own, or, with `per_cell` false, only
  /// totals (per-cell arrays refused for memory).
  CellCounters(std::uint64_t cells, const Vec3d& cell_size, bool per_cell = true);
  /// Counters whose per-cell counts go to `shared`, which other threads'
  /// counters share (count into it with SharedTally only).
  CellCounters(std::shared_ptr<CellArrays> shared, const Vec3d& cell_size);

  bool per_cell() const { return m_cells != nullptr; }

  /// The recorder of one query (accel/recorder.h): the walk's counts are
  /// added to the totals once at the end, with eq 24's prediction from the
  /// walked segment. With per-cell counting (the choice is a template
  /// argument, made per frame or per path, never per cell) it also counts
  /// each cell's visit: on grids of millions of cells the cache lines those
  /// writes touch are most of what statistics cost.
  template <PerCell Mode>
  class BasicTally {
   public:
    /// With `recent`, each step is also counted cold or warm against it.
    explicit BasicTally(CellCounters& owner, RecentCells* recent = nullptr)
        : m_owner(owner), m_cells(owner.m_cells.get()), m_recent(recent) {}
    ~BasicTally() {
      if constexpr (Mode != PerCell::no) ++m_owner.m_per_cell_queries;
    }
    BasicTally(const BasicTally&) = delete;
    BasicTally& operator=(const BasicTally&) = delete;

    template <class BoxFn>
    void cell(std::uint64_t c, int /*level*/, BoxFn&& /*box*/) {
      cell_known_cold(c, m_recent && m_recent->visit(c));
    }
    /// A step whose coldness another tally found (TeeTally).
    void cell_known_cold(std::uint64_t c, bool cold) {
      if constexpr (Mode != PerCell::no) count(m_cells->visits, c);
      m_cold = cold;
      m_cold_cells += cold;
    }
    bool last_cold() const { return m_cold; }
    void test() { m_cold_tests += m_cold; }
    void hit() {}
    /// The walk's own counts (kept in registers during the walk).
    void finish(const WalkCounts& w, const WalkSegment& segment) {
      ClassTotals& t = m_owner.totals;
      t.cold_cells += m_cold_cells;
      t.cold_tests += m_cold_tests;
      t.cells += w.cells;
      t.occupied_cells += w.occupied;
      t.refs += w.refs;
      t.tests += w.tests;
      t.mailbox_skips += w.skips;
      t.descents += w.descents;
      for (int k = 0; k < kMaxCellLevels; ++k) {
        t.level_cells[k] += w.level_cells[k];
        t.level_tests[k] += w.level_tests[k];
        t.level_refs[k] += w.level_refs[k];
      }
      const double predicted = predicted_cells_eq24(segment, m_owner.m_inv_cell);
      t.predicted_fixed += std::uint64_t(predicted * 1024.0 + 0.5);  // >= 0: rounds to nearest
    }

   private:
    static void count(SplitCounts& counts, std::uint64_t c) {
      if constexpr (Mode == PerCell::shared) counts.increment_shared(std::size_t(c));
      else counts.increment(std::size_t(c));
    }

    CellCounters& m_owner;
    CellArrays* m_cells;
    RecentCells* m_recent;
    bool m_cold = false;  ///< the step last entered was cold
    std::uint64_t m_cold_cells = 0, m_cold_tests = 0;
  };
  /// Counts per cell into this thread's own arrays.
  using Tally = BasicTally<PerCell::own>;
  /// Counts per cell into arrays shared with other threads.
  using SharedTally = BasicTally<PerCell::shared>;
  /// Counts only the totals.
  using TotalsTally = BasicTally<PerCell::no>;

  /// One walk counted in two sets of counters (a bounce ray in its depth's
  /// class and in its lobe's), each as a BasicTally would.
  template <PerCell Mode>
  class TeeTally {
   public:
    TeeTally(CellCounters& a, CellCounters& b, RecentCells* recent = nullptr) : m_a(a, recent), m_b(b) {}
    template <class BoxFn>
    void cell(std::uint64_t c, int level, BoxFn&& box) {
      m_a.cell(c, level, box);
      m_b.cell_known_cold(c, m_a.last_cold());  // one step, looked up once
    }
    void test() {
      m_a.test();
      m_b.test();
    }
    void hit() {}
    void finish(const WalkCounts& w, const WalkSegment& segment) {
      m_a.finish(w, segment);
      m_b.finish(w, segment);
    }

   private:
    BasicTally<Mode> m_a, m_b;
  };

  /// Queries counted per cell (all of them unless per-cell counting was
  /// sampled): the denominator of p_i.
  std::uint64_t per_cell_queries() const { return m_per_cell_queries; }

  /// Adds `other` into this (the per-thread merge); per-cell arrays that
  /// both share are already one.
  void merge(const CellCounters& other);
  /// Every count, in one order (totals, per-cell queries, then each cell's
  /// visits if counted per cell), appended to `out`; assign() reads them
  /// back from `in`, advancing it: how the ranks of one frame add theirs.
  void flatten(std::vector<std::uint64_t>& out) const;
  void assign(const std::uint64_t*& in);

  /// Per cell, in cell order: rays that visited it (p_i * rays).
  std::vector<std::uint64_t> visits() const { return m_cells->visits.all(); }
  /// The visits of cell i, without copying the array.
  std::uint64_t visits_at(std::size_t i) const { return m_cells->visits.at(i); }

  ClassTotals totals;

 private:
  std::shared_ptr<CellArrays> m_cells;  ///< null: totals only
  std::uint64_t m_per_cell_queries = 0;
  Vec3d m_inv_cell;  ///< 1 / cell size per axis, for eq 24 (0 where the size is not uniform)
};

}  // namespace kappa
