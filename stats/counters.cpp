#include "counters.h"

namespace kappa {

ClassTotals& ClassTotals::operator+=(const ClassTotals& o) {
  rays += o.rays;
  cells += o.cells;
  tests += o.tests;
  mailbox_skips += o.mailbox_skips;
  refs += o.refs;
  hits += o.hits;
  return *this;
}

void CellCounters::merge(const CellCounters& other) {
  for (std::size_t i = 0; i < m_cells.size() && i < other.m_cells.size(); ++i) {
    m_cells[i].visits += other.m_cells[i].visits;
    m_cells[i].tests += other.m_cells[i].tests;
    m_cells[i].hits += other.m_cells[i].hits;
  }
  totals += other.totals;
}

std::vector<std::uint64_t> CellCounters::visits() const {
  std::vector<std::uint64_t> v(m_cells.size());
  for (std::size_t i = 0; i < m_cells.size(); ++i) v[i] = m_cells[i].visits;
  return v;
}

}  // namespace kappa
