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

class CellCounters {
 public:
  /// `cells` = 0 keeps totals only (per-cell arrays refused for memory).
  explicit CellCounters(std::uint64_t cells) : visits(cells, 0), tests_in(cells, 0), hits_in(cells, 0) {}

  bool per_cell() const { return !visits.empty(); }

  // The Recorder interface.
  void cell(std::uint64_t c, std::uint32_t theta) {
    if (per_cell()) ++visits[c];
    m_current = c;
    ++totals.cells;
    totals.refs += theta;
  }
  void test() {
    if (per_cell()) ++tests_in[m_current];
    ++totals.tests;
  }
  void skip() { ++totals.mailbox_skips; }
  void hit() {
    if (per_cell()) ++hits_in[m_current];
  }

  /// Adds `other` into this (the per-thread merge).
  void merge(const CellCounters& other);

  std::vector<std::uint64_t> visits;    ///< rays that visited each cell
  std::vector<std::uint64_t> tests_in;  ///< triangle tests made in each cell
  std::vector<std::uint64_t> hits_in;   ///< tests in each cell that found a (new closest) hit
  ClassTotals totals;

 private:
  std::uint64_t m_current = 0;
};

}  // namespace kappa
