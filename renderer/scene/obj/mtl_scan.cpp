#include "renderer/scene/obj/mtl_scan.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "renderer/scene/obj/obj_limits.h"
#include "renderer/scene/obj/obj_scan.h"

namespace kappa {

std::string scan_mtl(const std::filesystem::path& file, const std::string& text) {
  std::string out;
  out.reserve(text.size() + 64);
  // A UTF-8 byte-order mark is not part of the first statement.
  std::istringstream lines(text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text);
  std::string raw;
  for (std::size_t line_no = 1; std::getline(lines, raw); ++line_no) {
    std::string_view body(raw);
    if (!body.empty() && body.back() == '\r') body.remove_suffix(1);
    // As the OBJ scan reads its lines: comments dropped, every blank a space.
    body = without_comment(body);
    std::string line;
    append_with_spaces(line, body);
    const auto tokens = split_ws(line);
    const bool colour = !tokens.empty() && (tokens[0] == "Ka" || tokens[0] == "Kd" || tokens[0] == "Ks" ||
                                            tokens[0] == "Ke" || tokens[0] == "Tf" || tokens[0] == "Kt");
    if (!colour) {
      out.append(line).push_back('\n');
      continue;
    }
    const std::string key(tokens[0]);
    if (tokens.size() != 2 && tokens.size() != 4)
      fail(file, line_no, key + " needs 1 or 3 numbers, found " + std::to_string(tokens.size() - 1));
    double v[3];
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string tok(tokens[k]);
      switch (parse_number(tokens[k], v[k - 1])) {
        case NumberStatus::invalid: fail(file, line_no, key + " component '" + tok + "' is not a number");
        case NumberStatus::out_of_range: fail(file, line_no, key + " component '" + tok + "' is out of the range of a double");
        case NumberStatus::ok: break;
      }
      if (!std::isfinite(v[k - 1])) fail(file, line_no, key + " component '" + tok + "' is not finite");
      if (std::abs(v[k - 1]) > kMaxCoordinate) {
        char limit[32];
        std::snprintf(limit, sizeof limit, "%.3g", kMaxCoordinate);
        fail(file, line_no, key + " component '" + tok + "' exceeds Kappa's limit of " + limit);
      }
    }
    if (tokens.size() == 2) {  // one component: the MTL convention is a grey, g = b = r
      const std::string r(tokens[1]);
      out.append(key).append(" ").append(r).append(" ").append(r).append(" ").append(r).push_back('\n');
    } else {
      out.append(line).push_back('\n');
    }
  }
  return out;
}

}  // namespace kappa
