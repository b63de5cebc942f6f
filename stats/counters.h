// Counters for one class of rays walked through the uniform grid: per cell
// (visits -> p_i, triangle tests, hits) and in total. A CellCounters is the
// Recorder of UniformGrid's templated walks (accel/grid_traverse.h): one per
// thread, merged once at the end. Counts are kept in locals during a ray and
// added per cell, never shared between threads.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/grid_resolution.h"

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
  /// locals, added to the totals once at the end. Visits, written at every
  /// step, are 32-bit and kept apart from tests and hits (written only when
  /// a triangle is tested): on grids of millions of cells the cache lines
  /// those writes touch are most of what statistics cost.
  class Tally {
   public:
    explicit Tally(CellCounters& owner)
        : m_owner(owner), m_visits(owner.per_cell() ? owner.m_visits.data() : nullptr) {}
    ~Tally() {
      ClassTotals& t = m_owner.totals;
      t.cells += m_cells;
      t.refs += m_refs;
      t.tests += m_tests;
      t.mailbox_skips += m_skips;
      // A ray visits a cell at most once, so no 32-bit count can overflow
      // before 2^32 - 1 queries: fold into 64 bits before that.
      if (++m_owner.m_queries_since_fold == m_owner.m_fold_every) m_owner.fold();
    }
    Tally(const Tally&) = delete;
    Tally& operator=(const Tally&) = delete;

    void cell(std::uint64_t c, int /*ix*/, int /*iy*/, int /*iz*/, std::uint32_t theta) {
      ++m_cells;
      m_refs += theta;
      m_current = c;
      if (m_visits) ++m_visits[c];
    }
    void test() {
      ++m_tests;
      if (m_visits) ++m_owner.m_tests[m_current];
    }
    void skip() { ++m_skips; }
    void hit() {
      if (m_visits) ++m_owner.m_hits[m_current];
    }

   private:
    CellCounters& m_owner;
    std::uint32_t* m_visits;
    std::uint64_t m_current = 0;
    std::uint64_t m_cells = 0, m_refs = 0, m_tests = 0, m_skips = 0;
  };

  /// Adds `other` into this (the per-thread merge).
  void merge(const CellCounters& other);

  /// Per cell, in cell order: rays that visited it (p_i * rays), triangle
  /// tests made in it, tests in it that found a (new closest) hit.
  std::vector<std::uint64_t> visits() const;
  const std::vector<std::uint64_t>& tests_in() const { return m_tests; }
  const std::vector<std::uint64_t>& hits_in() const { return m_hits; }

  ClassTotals totals;

 private:
  void fold();


  std::vector<std::uint32_t> m_visits;     ///< since the last fold
  std::vector<std::uint64_t> m_visits_64;  ///< folded visits (empty until the first fold)
  std::vector<std::uint64_t> m_tests, m_hits;
  std::uint64_t m_queries_since_fold = 0;
  std::uint64_t m_fold_every = kFoldEvery;
};

}  // namespace kappa
