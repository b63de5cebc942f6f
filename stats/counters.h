// Counters for one class of rays walked through the uniform grid: per cell
// (visits -> p_i, triangle tests, hits) and in total. A CellCounters is the
// Recorder of UniformGrid's templated walks (accel/grid_traverse.h): one per
// thread, merged once at the end. Totals are counted by the walk in
// registers and added once per ray; per-cell counts are added per cell,
// never shared between threads.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/grid.h"
#include "split_counts.h"
#include "zeroed_array.h"

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

class CellCounters {
 public:
  /// Queries between folds: a ray visits a cell at most once, so no 32-bit
  /// visit count can overflow in 2^31 queries.
  static constexpr std::uint64_t kFoldEvery = std::uint64_t(1) << 31;

  /// Counters for the cells of a grid of resolution `res`; with `per_cell`
  /// false only totals are kept (per-cell arrays refused for memory).
  /// `fold_every` (queries between folds of the 32-bit visit counts into 64
  /// bits) is for tests; it must stay at most 2^32 - 1.
  explicit CellCounters(const GridResolution& res, bool per_cell = true, std::uint64_t fold_every = kFoldEvery);

  bool per_cell() const { return !m_visits.empty(); }

  /// The recorder of one query (UniformGrid's templated walks): counts in
  /// locals, added to the totals once at the end. With PerCell (the choice is
  /// a template argument, made per frame or per path, never per cell) it also
  /// counts per cell: visits, written at every step, are 32-bit and kept
  /// apart from tests and hits (written only when a triangle is tested): on
  /// grids of millions of cells the cache lines those writes touch are most
  /// of what statistics cost.
  template <bool PerCell>
  class BasicTally {
   public:
    explicit BasicTally(CellCounters& owner) : m_owner(owner) {}
    ~BasicTally() {
      if constexpr (PerCell) {
        ++m_owner.m_per_cell_queries;
        // A ray visits a cell at most once, so no 32-bit count can overflow
        // before 2^32 - 1 queries: fold into 64 bits before that.
        if (++m_owner.m_queries_since_fold == m_owner.m_fold_every) m_owner.fold();
      }
    }
    BasicTally(const BasicTally&) = delete;
    BasicTally& operator=(const BasicTally&) = delete;

    void cell(std::uint64_t c, int /*ix*/, int /*iy*/, int /*iz*/) {
      if constexpr (PerCell) {
        m_current = c;
        ++m_owner.m_visits[c];
      }
    }
    void test() {
      if constexpr (PerCell) m_owner.m_tests.increment(m_current);
    }
    void hit() {
      if constexpr (PerCell) m_owner.m_hits.increment(m_current);
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
    CellCounters& m_owner;
    std::uint64_t m_current = 0;
  };
  /// Counts per cell; only for counters with per_cell().
  using Tally = BasicTally<true>;
  /// Counts only the totals.
  using TotalsTally = BasicTally<false>;

  /// Queries counted per cell (all of them unless per-cell counting was
  /// sampled): the denominator of p_i.
  std::uint64_t per_cell_queries() const { return m_per_cell_queries; }

  /// Adds `other` into this (the per-thread merge).
  void merge(const CellCounters& other);

  /// Per cell, in cell order: rays that visited it (p_i * rays), triangle
  /// tests made in it, tests in it that found a (new closest) hit.
  std::vector<std::uint64_t> visits() const;
  /// The visits of cell i, without copying the array.
  std::uint64_t visits_at(std::size_t i) const {
    return std::uint64_t(m_visits[i]) + (m_visits_64.empty() ? 0 : m_visits_64[i]);
  }
  std::size_t cell_count() const { return m_visits.size(); }
  std::vector<std::uint64_t> tests_in() const { return m_tests.all(); }
  std::vector<std::uint64_t> hits_in() const { return m_hits.all(); }

  ClassTotals totals;

 private:
  void fold();


  ZeroedArray<std::uint32_t> m_visits;     ///< since the last fold
  ZeroedArray<std::uint64_t> m_visits_64;  ///< folded visits (empty until the first fold)
  SplitCounts m_tests, m_hits;  ///< 64-bit counts, 4 bytes of traffic a cell (split_counts.h)
  std::uint64_t m_queries_since_fold = 0;
  std::uint64_t m_per_cell_queries = 0;
  std::uint64_t m_fold_every = kFoldEvery;
};

}  // namespace kappa
