#include "counters.h"

#include <cstring>
#include <type_traits>

namespace kappa {

ClassTotals& ClassTotals::operator+=(const ClassTotals& o) {
  rays += o.rays;
  cells += o.cells;
  occupied_cells += o.occupied_cells;
  tests += o.tests;
  mailbox_skips += o.mailbox_skips;
  alpha_tests += o.alpha_tests;
  refs += o.refs;
  hits += o.hits;
  for (int k = 0; k < kMaxCellLevels; ++k) {
    level_cells[k] += o.level_cells[k];
    level_tests[k] += o.level_tests[k];
    level_refs[k] += o.level_refs[k];
  }
  predicted_fixed += o.predicted_fixed;
  cold_cells += o.cold_cells;
  cold_tests += o.cold_tests;
  descents += o.descents;
  return *this;
}

namespace {

Vec3d inverse(const Vec3d& cell_size) {
  Vec3d inv;
  for (int a = 0; a < 3; ++a) (a == 0 ? inv.x : a == 1 ? inv.y : inv.z) = cell_size[a] > 0 ? 1.0 / cell_size[a] : 0.0;
  return inv;
}

}  // namespace

CellCounters::CellCounters(std::uint64_t cells, const Vec3d& cell_size, bool per_cell)
    : m_inv_cell(inverse(cell_size)) {
  if (per_cell) m_cells = std::make_shared<CellArrays>(cells);
}

CellCounters::CellCounters(std::shared_ptr<CellArrays> shared, const Vec3d& cell_size)
    : m_cells(std::move(shared)), m_inv_cell(inverse(cell_size)) {}

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
  }
  totals += other.totals;
  m_per_cell_queries += other.m_per_cell_queries;
}

// ClassTotals is counts only, every one a 64-bit integer: copied as such.
static_assert(std::is_trivially_copyable_v<ClassTotals> && sizeof(ClassTotals) % sizeof(std::uint64_t) == 0);
constexpr std::size_t kTotalsWords = sizeof(ClassTotals) / sizeof(std::uint64_t);

void CellCounters::flatten(std::vector<std::uint64_t>& out) const {
  const std::size_t at = out.size();
  out.resize(at + kTotalsWords);
  std::memcpy(out.data() + at, &totals, sizeof(ClassTotals));
  out.push_back(m_per_cell_queries);
  if (m_cells)
    for (std::size_t i = 0; i < m_cells->visits.size(); ++i) out.push_back(m_cells->visits.at(i));
}

void CellCounters::assign(const std::uint64_t*& in) {
  std::memcpy(&totals, in, sizeof(ClassTotals));
  in += kTotalsWords;
  m_per_cell_queries = *in++;
  if (m_cells)
    for (std::size_t i = 0; i < m_cells->visits.size(); ++i) m_cells->visits.set(i, *in++);
}

}  // namespace kappa
