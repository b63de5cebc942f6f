#include "counters.h"

namespace kappa {

ClassTotals& ClassTotals::operator+=(const ClassTotals& o) {
  rays += o.rays;
  cells += o.cells;
  tests += o.tests;
  mailbox_skips += o.mailbox_skips;
  refs += o.refs;
  hits += o.hits;
  predicted_fixed += o.predicted_fixed;
  return *this;
}

CellCounters::CellCounters(const GridResolution& res, bool per_cell) {
  if (per_cell) m_cells = std::make_shared<CellArrays>(res.cells());
}

CellCounters::CellCounters(std::shared_ptr<CellArrays> shared) : m_cells(std::move(shared)) {}

namespace {

/// Adds b into a where b counted something: pages of cells no ray visited
/// stay untouched zero pages in a (see ZeroedArray).
void add_counts(SplitCounts& a, const SplitCounts& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (const std::uint64_t v = b.at(i); v != 0) a.add(i, v);
}

}  // namespace

void CellCounters::merge(const CellCounters& other) {
  if (m_cells && other.m_cells && m_cells != other.m_cells) {
    add_counts(m_cells->visits, other.m_cells->visits);
    add_counts(m_cells->tests, other.m_cells->tests);
    add_counts(m_cells->hits, other.m_cells->hits);
  }
  totals += other.totals;
  m_per_cell_queries += other.m_per_cell_queries;
}

}  // namespace kappa
