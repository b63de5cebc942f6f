// Warnings of one glTF file, each kind once ("normal maps are not modelled"
// once, not once per material), naming the file and the JSON pointer of the
// first element that raised it.
#pragma once

#include <filesystem>
#include <set>
#include <string>

#include "core/error.h"

namespace kappa {

class GltfWarnings {
 public:
  GltfWarnings(const std::filesystem::path& file, Warnings& out) : m_file(file), m_out(out) {}

  /// Warns `message` at `pointer` unless `kind` was warned already.
  void once(const std::string& kind, const std::string& pointer, const std::string& message) {
    if (!m_kinds.insert(kind).second) return;
    m_out.push_back(located(m_file, 0, pointer + ": " + message));
  }

 private:
  const std::filesystem::path& m_file;
  Warnings& m_out;
  std::set<std::string> m_kinds;
};

}  // namespace kappa
