#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/input_error.h"

namespace kappa {
namespace {

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& why) {
  throw InputError(file.string() + ": " + why);
}

}  // namespace

void check_input_file(const std::filesystem::path& file, const char* kind) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) refuse(file, "file not found");
    refuse(file, std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) refuse(file, std::string("is a directory, not ") + kind);
  if (!S_ISREG(st.st_mode)) refuse(file, std::string("is not a regular file (a FIFO, socket or device), not ") + kind);
  if (std::uint64_t(st.st_size) > kMaxInputBytes)
    refuse(file, "is larger than Kappa's input limit of 16 GiB (" + std::to_string(st.st_size) + " bytes)");
  // Readable? Opened without blocking (it is a regular file, so O_NONBLOCK
  // changes nothing but is harmless if it changed under us).
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK);
  if (fd < 0) refuse(file, std::strerror(errno));
  ::close(fd);
}

std::string read_input_file(const std::filesystem::path& file, const char* kind) {
  check_input_file(file, kind);
  std::ifstream in(file, std::ios::binary);
  if (!in) refuse(file, "cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace kappa
