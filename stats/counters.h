// Counters for one class of rays walked through the uniform grid: per cell
// (visits -> p_i, triangle tests, hits) and in total. A CellCounters is the
// Recorder of UniformGrid's templated walks (accel/grid_traverse.h): one per
// thread, merged once at the end. Counts are kept in locals during a ray and
// added per cell, never shared between threads.
#pragma once

#include <cstdint>
#include <vector>

namespace kappa {

/// Totals over all rays of a class (64-bit: renders cast billions).
struct ClassTotals {
  std::uint64_t rays = 0;
  std::uint64_t cells = 0;          ///< cells visited, summed over rays
  std::uint64_t tests = 0;          ///< triangle tests performed (after mailboxing)
  std::uint64_t mailbox_skips = 0;  ///< tests avoided by the mailbox
  std::uint64_t refs = 0;           ///< sum of Theta_i over visited cells (before mailboxing)
  std::uint64_t hits = 0;           ///< rays that hit something

  ClassTotals& operator+=(const ClassTotals& o);
};

/// One cell's counts for one class. Kept together so that a visit touches
/// one cache line, not three arrays: on grids of millions of cells the
/// counters' cache misses are most of what statistics cost.
struct CellCount {
  std::uint64_t visits = 0;  ///< rays that visited the cell
  std::uint64_t tests = 0;   ///< triangle tests made in it
  std::uint64_t hits = 0;    ///< tests in it that found a (new closest) hit
  bool operator==(const CellCount&) const = default;
};

class CellCounters {
 public:
  /// `cells` = 0 keeps totals only (per-cell arrays refused for memory).
  explicit CellCounters(std::uint64_t cells) : m_cells(cells) {}

  bool per_cell() const { return !m_cells.empty(); }

  // The Recorder interface.
  void cell(std::uint64_t c, std::uint32_t theta) {
    m_current = per_cell() ? &m_cells[c] : nullptr;
    if (m_current) ++m_current->visits;
    ++totals.cells;
    totals.refs += theta;
  }
  void test() {
    if (m_current) ++m_current->tests;
    ++totals.tests;
  }
  void skip() { ++totals.mailbox_skips; }
  void hit() {
    if (m_current) ++m_current->hits;
  }

  /// Adds `other` into this (the per-thread merge).
  void merge(const CellCounters& other);

  const std::vector<CellCount>& cells() const { return m_cells; }
  /// Visits per cell (p_i * rays), in cell order.
  std::vector<std::uint64_t> visits() const;

  ClassTotals totals;

 private:
  std::vector<CellCount> m_cells;
  CellCount* m_current = nullptr;
};

}  // namespace kappa
