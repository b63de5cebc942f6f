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

CellCounters::CellCounters(const GridResolution& res, bool per_cell, std::uint64_t fold_every)
    : m_fold_every(fold_every) {
  if (!per_cell) return;
  m_visits = ZeroedArray<std::uint32_t>(res.cells());
  m_tests = SplitCounts(res.cells());
  m_hits = SplitCounts(res.cells());
}

void CellCounters::fold() {
  if (m_visits_64.empty()) m_visits_64 = ZeroedArray<std::uint64_t>(m_visits.size());
  for (std::size_t i = 0; i < m_visits.size(); ++i) {
    m_visits_64[i] += m_visits[i];
    m_visits[i] = 0;
  }
  m_queries_since_fold = 0;
}

void CellCounters::merge(const CellCounters& other) {
  if (per_cell() && other.per_cell()) {
    if (m_visits_64.empty()) m_visits_64 = ZeroedArray<std::uint64_t>(m_visits.size());
    // Written only where other counted something: pages of cells no ray
    // visited stay untouched zero pages (see ZeroedArray).
    for (std::size_t b = 0; b < m_visits.size(); ++b) {
      const std::uint64_t v = std::uint64_t(other.m_visits[b]) + (other.m_visits_64.empty() ? 0 : other.m_visits_64[b]);
      if (v != 0) m_visits_64[b] += v;
    }
    for (std::size_t i = 0; i < m_tests.size(); ++i) {
      if (const std::uint64_t t = other.m_tests.at(i); t != 0) m_tests.add(i, t);
      if (const std::uint64_t h = other.m_hits.at(i); h != 0) m_hits.add(i, h);
    }
  }
  totals += other.totals;
  m_per_cell_queries += other.m_per_cell_queries;
}

std::vector<std::uint64_t> CellCounters::visits() const {
  std::vector<std::uint64_t> v(m_visits.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = visits_at(i);
  return v;
}

}  // namespace kappa
