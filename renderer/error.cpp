#include "error.h"

namespace kappa {

std::string located(const std::filesystem::path& file, std::size_t line, const std::string& message) {
  // Built with append: GCC 12 warns falsely (-Wrestrict) on chained operator+.
  std::string s = file.string();
  if (line > 0) s.append(":").append(std::to_string(line));
  s.append(": ").append(message);
  return s;
}

void fail(const std::filesystem::path& file, std::size_t line, const std::string& message) {
  throw InputError(located(file, line, message));
}

}  // namespace kappa
