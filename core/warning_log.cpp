#include "core/warning_log.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace kappa {

std::string warning_kind(const std::string& text) {
  std::size_t start = 0;
  // The location: everything before the first ": ", when it holds no space
  // but in a path's own way (a location is a path, maybe ":line").
  if (const std::size_t colon = text.find(": "); colon != std::string::npos) {
    const std::string head = text.substr(0, colon);
    const bool looks_like_path = head.find('/') != std::string::npos || head.find('.') != std::string::npos;
    if (looks_like_path && head.find(' ') == std::string::npos) start = colon + 2;
  }
  std::string kind;
  for (std::size_t i = start; i < text.size();) {
    const char c = text[i];
    if (c == '\'') {
      const std::size_t close = text.find('\'', i + 1);
      if (close != std::string::npos) {
        kind += "'...'";
        i = close + 1;
        continue;
      }
    }
    if (c >= '0' && c <= '9') {
      kind += 'N';
      while (i < text.size() && ((text[i] >= '0' && text[i] <= '9') || text[i] == '.' || text[i] == ',')) ++i;
      continue;
    }
    kind += c;
    ++i;
  }
  return kind;
}

void WarningLog::add(const std::string& text) {
  const std::string kind = warning_kind(text);
  std::lock_guard<std::mutex> lock(m_mutex);
  Entry* entry = nullptr;
  for (Entry& e : m_entries)
    if (e.kind.kind == kind) entry = &e;
  if (!entry) {
    m_entries.push_back({{kind, text, 0}, 0});
    entry = &m_entries.back();
  }
  if (++entry->kind.count <= kWarningsShownPerKind && m_printing)
    std::fprintf(stderr, "kappa: warning: %s\n", printable_line(text).c_str());
}

void WarningLog::finish() {
  std::lock_guard<std::mutex> lock(m_mutex);
  for (Entry& e : m_entries) {
    const std::uint64_t shown = std::min(e.kind.count, kWarningsShownPerKind);
    const std::uint64_t more = e.kind.count - shown - e.summarised;
    if (more == 0) continue;
    if (m_printing)
      std::fprintf(stderr, "kappa: warning: ... and %llu more like it: %s\n", static_cast<unsigned long long>(more),
                 printable_line(e.kind.kind).c_str());
    e.summarised += more;
  }
}

std::vector<WarningKind> WarningLog::kinds() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  std::vector<WarningKind> out;
  for (const Entry& e : m_entries) out.push_back(e.kind);
  return out;
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) warning_log().add(w);
}

WarningLog& warning_log() {
  static WarningLog log;
  return log;
}

}  // namespace kappa
