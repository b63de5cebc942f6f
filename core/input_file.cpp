#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>

#include "core/byte_size.h"
#include "core/hash.h"
#include "core/input_error.h"
#include "core/memory_need.h"
#include "core/physical_memory.h"

namespace kappa {
namespace {

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& why) {
  throw InputError(file.string() + ": " + why);
}

[[noreturn]] void refuse_at(const std::filesystem::path& file, std::uint64_t line, const std::string& why) {
  throw InputError(file.string() + ":" + std::to_string(line) + ": " + why);
}

std::string key_of(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
  return (ec ? file : absolute).lexically_normal().string();
}

std::mutex g_records_mutex;
std::map<std::string, InputRecord>& records() {
  static std::map<std::string, InputRecord> by_path;
  return by_path;
}

/// Judges text as it arrives, block by block: the line it is at, the length
/// of the line so far, and a UTF-8 sequence cut by a block's end.
class TextJudge {
 public:
  TextJudge(const std::filesystem::path& file, const char* kind, InputContent content)
      : m_file(file), m_kind(kind), m_content(content) {
    // "an OBJ file" -> "OBJ file" and "OBJ", for "not a text OBJ file".
    m_noun = m_kind.substr(m_kind.rfind("an ", 0) == 0 ? 3 : m_kind.rfind("a ", 0) == 0 ? 2 : 0);
    m_short = m_noun.size() > 5 && m_noun.compare(m_noun.size() - 5, 5, " file") == 0 ? m_noun.substr(0, m_noun.size() - 5)
                                                                                      : m_noun;
  }

  void take(const unsigned char* p, std::size_t n) {
    if (m_at == 0 && n >= 2 && ((p[0] == 0xFE && p[1] == 0xFF) || (p[0] == 0xFF && p[1] == 0xFE)))
      refuse_at(m_file, 1, "UTF-16 encoding is not supported (save the " + m_short + " as UTF-8 or ASCII)");
    for (std::size_t i = 0; i < n; ++i) {
      const unsigned char c = p[i];
      if (m_pending > 0) {  // inside a UTF-8 sequence
        if ((c & 0xC0) != 0x80) bad_utf8();
        --m_pending;
        ++m_line_bytes;
        continue;
      }
      if (c == '\n') {
        ++m_line;
        m_line_bytes = 0;
        continue;
      }
      if (++m_line_bytes > kMaxTextLineBytes)
        refuse_at(m_file, m_line, "a line longer than " + byte_size(kMaxTextLineBytes) + ": not a text " + m_noun);
      // DEL is a control character in text, but valid UTF-8 in JSON's strings.
      if ((c < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') ||
          (c == 0x7F && m_content != InputContent::utf8)) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", c);
        refuse_at(m_file, m_line, std::string("binary data (byte ") + hex + "): not a text " + m_noun);
      }
      if (c >= 0x80 && m_content == InputContent::utf8) {
        if (c >= 0xC2 && c <= 0xDF) m_pending = 1;
        else if (c >= 0xE0 && c <= 0xEF) m_pending = 2;
        else if (c >= 0xF0 && c <= 0xF4) m_pending = 3;
        else bad_utf8();
      }
    }
    m_at += n;
  }

  void end() {
    if (m_pending > 0) bad_utf8();
  }

 private:
  [[noreturn]] void bad_utf8() {
    refuse_at(m_file, m_line, "a byte that is not UTF-8: not a " + m_noun + " (JSON is UTF-8)");
  }

  const std::filesystem::path& m_file;
  std::string m_kind, m_noun, m_short;
  InputContent m_content;
  std::uint64_t m_at = 0, m_line = 1, m_line_bytes = 0;
  int m_pending = 0;
};

}  // namespace

std::uint64_t max_input_bytes() { return usable_memory_bytes() / 4; }

void check_input_file(const std::filesystem::path& file, const char* kind) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) {
      // A link that leads nowhere is not a missing file.
      struct stat link {};
      if (::lstat(file.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
        refuse(file, "is a symbolic link to '" + std::filesystem::read_symlink(file).string() + "', which does not exist");
      refuse(file, "file not found");
    }
    if (err == ENOTDIR) refuse(file, "file not found (a part of its path is not a folder)");
    if (err == ELOOP) refuse(file, "a loop of symbolic links");
    if (err == EACCES) refuse(file, "Permission denied (a folder on its path cannot be searched)");
    refuse(file, std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) refuse(file, std::string("is a directory, not ") + kind);
  if (!S_ISREG(st.st_mode)) refuse(file, std::string("is not a regular file (a FIFO, socket or device), not ") + kind);
  if (std::uint64_t(st.st_size) > max_input_bytes())
    refuse(file, "is " + byte_size(std::uint64_t(st.st_size)) + ", larger than Kappa's input limit of " +
                     byte_size(max_input_bytes()) + " (a quarter of the " + byte_size(usable_memory_bytes()) +
                     " this process may use: reading a file needs a few times its size)");
  // Readable? Opened without blocking (it is a regular file, so O_NONBLOCK
  // changes nothing but is harmless if it changed under us).
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK);
  if (fd < 0) refuse(file, std::strerror(errno));
  ::close(fd);
}

std::string read_input_file(const std::filesystem::path& file, const char* kind, InputContent content) {
  check_input_file(file, kind);
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) refuse(file, std::string("cannot open for reading: ") + std::strerror(errno));
  struct stat st {};
  // What was opened is still a regular file (not one swapped for a FIFO or
  // /dev/zero since the check).
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    refuse(file, std::string("is not a regular file (a FIFO, socket or device), not ") + kind);
  }
  std::string bytes;
  std::uint64_t hash = kFnv1aOffset;
  TextJudge judge(file, kind, content);
  try {
    const MemoryNeed need("reading '" + file.string() + "'", std::uint64_t(st.st_size));
    // One block first; once it passes the judge, room for the whole file
    // (and the byte that finds its end) at once: the memory is what the
    // content needs, not a doubling's, and a file bad from its first block
    // costs one block.
    constexpr std::size_t kBlock = std::size_t(1) << 20;
    bytes.reserve(std::min<std::uint64_t>(std::uint64_t(st.st_size) + 1, kBlock));
    bool whole_reserved = false;
    for (;;) {
      const std::size_t at = bytes.size();
      if (at > 0 && !whole_reserved) {
        bytes.reserve(std::max<std::uint64_t>(std::uint64_t(st.st_size) + 1, at + 1));
        whole_reserved = true;
      }
      if (bytes.capacity() == at) bytes.reserve(at + kBlock);  // the file grew since stat()
      const std::size_t room = std::min(kBlock, bytes.capacity() - at);
      bytes.resize(at + room);
      const ssize_t n = ::read(fd, bytes.data() + at, room);
      if (n < 0 && errno == EINTR) {
        bytes.resize(at);
        continue;
      }
      if (n < 0) refuse(file, std::string("cannot read: ") + std::strerror(errno));
      bytes.resize(at + std::size_t(n));
      if (n == 0) break;
      // A file that grew past the limit while being read is refused too.
      if (bytes.size() > max_input_bytes()) refuse(file, "grew past Kappa's input limit while being read");
      const auto* block = reinterpret_cast<const unsigned char*>(bytes.data() + at);
      if (content != InputContent::binary) judge.take(block, std::size_t(n));
      hash = fnv1a64(std::string_view(bytes.data() + at, std::size_t(n)), hash);
    }
    if (content != InputContent::binary) judge.end();
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  {
    const std::lock_guard<std::mutex> lock(g_records_mutex);
    records()[key_of(file)] = {file, bytes.size(), hash};
  }
  return bytes;
}

std::optional<InputRecord> input_read(const std::filesystem::path& file) {
  const std::lock_guard<std::mutex> lock(g_records_mutex);
  const auto it = records().find(key_of(file));
  if (it == records().end()) return std::nullopt;
  return it->second;
}

}  // namespace kappa
