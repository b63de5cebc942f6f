#include "core/error.h"

#include <cstdio>
#include <cstring>


namespace kappa {

std::string located(const std::filesystem::path& file, std::size_t line, const std::string& message) {
  // Built with append: GCC 12 warns falsely (-Wrestrict) on chained operator+.
  std::string s = file.string();
  if (line > 0) s.append(":").append(std::to_string(line));
  s.append(": ").append(message);
  return s;
}

void fail_output(const std::filesystem::path& file, const std::string& message, int err) {
  throw OutputError(located(file, 0, err != 0 ? message + ": " + std::strerror(err) : message));
}

void fail(const std::filesystem::path& file, std::size_t line, const std::string& message) {
  throw InputError(located(file, line, message));
}

namespace {

/// Length of the valid UTF-8 sequence starting at s[i], or 0 if there is none.
std::size_t utf8_sequence_length(const std::string& s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0 && c >= 0xC2) n = 2;
  else if ((c & 0xF0) == 0xE0) n = 3;
  else if ((c & 0xF8) == 0xF0 && c <= 0xF4) n = 4;
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  return n;
}

}  // namespace

std::string printable_line(const std::string& message) {
  std::string out;
  for (std::size_t i = 0; i < message.size();) {
    const std::size_t n = utf8_sequence_length(message, i);
    if (n == 0) {
      static const char* kHex = "0123456789ABCDEF";
      const auto c = static_cast<unsigned char>(message[i]);
      out.append("\\x").push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 15]);
      i += 1;
    } else if (message[i] == '\n' || message[i] == '\r') {
      out.push_back(' ');
      i += 1;
    } else {
      out.append(message, i, n);
      i += n;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace kappa
