// Counters for one class of rays walked through the uniform grid: per cell
// (visits -> p_i, triangle tests, hits) and in total. A CellCounters is the
// Recorder of UniformGrid's templated walks (accel/grid_traverse.h): one per
// thread, merged once at the end. Totals are counted by the walk in
// registers and added once per ray; per-cell counts are added per cell, into
// the thread's own arrays or, for sampled paths, into arrays all threads
// share.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/grid.h"
#include "split_counts.h"

namespace kappa {

/// Totals over all rays of a class (64-bit: renders cast billions).
struct ClassTotals {
  std::uint64_t rays = 0;
  std::uint64_t cells = 0;          ///< cells visited, summed over rays
  std::uint64_t tests = 0;          ///< triangle tests performed (after mailboxing)
  std::uint64_t mailbox_skips = 0;  ///< tests avoided by the mailbox
  std::uint64_t refs = 0;           ///< sum of Theta_i over visited cells (before mailboxing)
  std::uint64_t hits = 0;           ///< rays that hit something
  /// Sum over rays of the model's predicted cells (WalkCounts) in 1/1024
  /// units: an integer, so totals do not depend on how threads split rays.
  std::uint64_t predicted_fixed = 0;

  double predicted_cells() const { return double(predicted_fixed) / 1024.0; }

  ClassTotals& operator+=(const ClassTotals& o);
};

/// Per-cell counts of one class of rays: visits (-> p_i), triangle tests
/// made in the cell and tests that found a (new closest) hit there.
struct CellArrays {
  explicit CellArrays(std::size_t cells) : visits(cells), tests(cells), hits(cells) {}
  SplitCounts visits, tests, hits;
};

/// How a walk counts per cell: not at all (totals only), into its thread's
/// own arrays, or into arrays every thread shares. Shared arrays take atomic
/// increments: right for sampled paths, which write rarely, as one copy then
/// serves every thread (no per-thread memory, no merge); wrong for counting
/// every path, where threads would fight over the same cache lines.
enum class PerCell { no, own, shared };

class CellCounters {
 public:
  /// Counters for the cells of a grid of resolution `res`, with per-cell
  /// arrays of their own, or, with `per_cell` false, only totals (per-cell
  /// arrays refused for memory).
  explicit CellCounters(const GridResolution& res, bool per_cell = true);
  /// Counters whose per-cell counts go to `shared`, which other threads'
  /// counters share (count into it with SharedTally only).
  explicit CellCounters(std::shared_ptr<CellArrays> shared);

  bool per_cell() const { return m_cells != nullptr; }

  /// The recorder of one query (UniformGrid's templated walks): counts in
  /// locals, added to the totals once at the end. With per-cell counting
  /// (the choice is a template argument, made per frame or per path, never
  /// per cell) it also counts per cell: visits, written at every step, are
  /// kept apart from tests and hits (written only when a triangle is
  /// tested): on grids of millions of cells the cache lines those writes
  /// touch are most of what statistics cost.
  template <PerCell Mode>
  class BasicTally {
   public:
    explicit BasicTally(CellCounters& owner) : m_owner(owner), m_cells(owner.m_cells.get()) {}
    ~BasicTally() {
      if constexpr (Mode != PerCell::no) ++m_owner.m_per_cell_queries;
    }
    BasicTally(const BasicTally&) = delete;
    BasicTally& operator=(const BasicTally&) = delete;

    void cell(std::uint64_t c, int /*ix*/, int /*iy*/, int /*iz*/) {
      if constexpr (Mode != PerCell::no) {
        m_current = c;
        count(m_cells->visits, c);
      }
    }
    void test() {
      if constexpr (Mode != PerCell::no) count(m_cells->tests, m_current);
    }
    void hit() {
      if constexpr (Mode != PerCell::no) count(m_cells->hits, m_current);
    }
    /// The walk's own counts (kept in registers during the walk).
    void finish(const WalkCounts& w) {
      ClassTotals& t = m_owner.totals;
      t.cells += w.cells;
      t.refs += w.refs;
      t.tests += w.tests;
      t.mailbox_skips += w.skips;
      t.predicted_fixed += std::uint64_t(w.predicted_cells * 1024.0 + 0.5);  // >= 0: rounds to nearest
    }

   private:
    static void count(SplitCounts& counts, std::uint64_t c) {
      if constexpr (Mode == PerCell::shared) counts.increment_shared(std::size_t(c));
      else counts.increment(std::size_t(c));
    }

    CellCounters& m_owner;
    CellArrays* m_cells;
    std::uint64_t m_current = 0;
  };
  /// Counts per cell into this thread's own arrays.
  using Tally = BasicTally<PerCell::own>;
  /// Counts per cell into arrays shared with other threads.
  using SharedTally = BasicTally<PerCell::shared>;
  /// Counts only the totals.
  using TotalsTally = BasicTally<PerCell::no>;

  /// Queries counted per cell (all of them unless per-cell counting was
  /// sampled): the denominator of p_i.
  std::uint64_t per_cell_queries() const { return m_per_cell_queries; }

  /// Adds `other` into this (the per-thread merge); per-cell arrays that
  /// both share are already one.
  void merge(const CellCounters& other);

  /// Per cell, in cell order: rays that visited it (p_i * rays), triangle
  /// tests made in it, tests in it that found a (new closest) hit.
  std::vector<std::uint64_t> visits() const { return m_cells->visits.all(); }
  /// The visits of cell i, without copying the array.
  std::uint64_t visits_at(std::size_t i) const { return m_cells->visits.at(i); }
  std::vector<std::uint64_t> tests_in() const { return m_cells->tests.all(); }
  std::vector<std::uint64_t> hits_in() const { return m_cells->hits.all(); }

  ClassTotals totals;

 private:
  std::shared_ptr<CellArrays> m_cells;  ///< null: totals only
  std::uint64_t m_per_cell_queries = 0;
};

}  // namespace kappa
