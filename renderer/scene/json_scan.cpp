#include "renderer/scene/json_scan.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <set>
#include <vector>

#include "core/error.h"

namespace kappa {

void check_json_keys_and_numbers(const std::filesystem::path& file, const std::string& text) {
  // One entry per open container: the keys seen so far, for objects.
  struct Container {
    bool object;
    std::set<std::string> keys;
  };
  std::vector<Container> open;
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '{' || c == '[') {
      open.push_back({c == '{', {}});
    } else if (c == '}' || c == ']') {
      if (!open.empty()) open.pop_back();
    } else if (c == '"') {
      // A string, with its escapes; a key if a ':' follows it.
      std::string s;
      std::size_t j = i + 1;
      for (; j < text.size() && text[j] != '"'; ++j) {
        if (text[j] == '\\' && j + 1 < text.size()) s += text[j++];
        s += text[j];
      }
      std::size_t k = j + 1;
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k])) && text[k] != '\n') ++k;
      if (k < text.size() && text[k] == ':' && !open.empty() && open.back().object &&
          !open.back().keys.insert(s).second)
        fail(file, line, "key '" + s + "' appears twice in one object (which value is meant?)");
      i = j;
    } else if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) {
      std::size_t j = i;
      while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '-' ||
                                 text[j] == '+' || text[j] == '.' || text[j] == 'e' || text[j] == 'E'))
        ++j;
      double v = 0;
      const auto [end, ec] = std::from_chars(text.data() + i, text.data() + j, v);
      if (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(v)))
        fail(file, line, "number '" + text.substr(i, j - i) + "' does not fit a double");
      i = j - 1;
    }
  }
}

std::string line_and_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

}  // namespace kappa
