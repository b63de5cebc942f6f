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
  for (std::size_t i = 0; i < visits.size() && i < other.visits.size(); ++i) {
    visits[i] += other.visits[i];
    tests_in[i] += other.tests_in[i];
    hits_in[i] += other.hits_in[i];
  }
  totals += other.totals;
}

}  // namespace kappa
