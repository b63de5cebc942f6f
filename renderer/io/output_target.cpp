#include "renderer/io/output_target.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"

namespace kappa {
namespace {

namespace fs = std::filesystem;

/// Linux's limit on the links one path resolution follows (MAXSYMLINKS).
constexpr int kMaxLinks = 40;

bool all_digits(const std::string& s) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

/// Whether the canonical folder `folder` is this process's descriptor table:
/// /proc/PID/fd, or /proc/PID/task/TID/fd (what /proc/thread-self leads to).
bool is_own_descriptor_folder(const fs::path& folder) {
  std::vector<std::string> parts;
  for (const auto& part : folder) parts.push_back(part.string());
  const std::string pid = std::to_string(::getpid());
  if (parts.size() == 4) return parts[0] == "/" && parts[1] == "proc" && parts[2] == pid && parts[3] == "fd";
  return parts.size() == 6 && parts[0] == "/" && parts[1] == "proc" && parts[2] == pid && parts[3] == "task" &&
         all_digits(parts[4]) && parts[5] == "fd";
}

/// Whether `folder` (canonical) is /dev or /proc or inside them, but for
/// /dev/shm: a memory file system where files are made and replaced as
/// anywhere else.
bool in_system_folder(const fs::path& folder) {
  auto part = folder.begin();
  if (part == folder.end() || *part != "/") return false;
  ++part;
  if (part == folder.end()) return false;
  if (*part == "proc") return true;
  if (*part != "dev") return false;
  ++part;
  return part == folder.end() || *part != "shm";
}

/// Standard descriptors that were closed when the process started (held by
/// /dev/null since, see hold_closed_standard_descriptors).
bool g_closed_at_start[3] = {false, false, false};

OutputTarget open_descriptor(const fs::path& given, int descriptor) {
  const int flags = ::fcntl(descriptor, F_GETFL);
  if (flags < 0 || (descriptor >= 0 && descriptor <= 2 && g_closed_at_start[descriptor])) fail(given, 0, "cannot write: it leads to " + descriptor_name(descriptor) + ", which is closed");
#ifdef O_PATH
  const bool path_only = (flags & O_PATH) != 0;
#else
  const bool path_only = false;
#endif
  if (path_only || (flags & O_ACCMODE) == O_RDONLY)
    fail(given, 0, "cannot write: it leads to " + descriptor_name(descriptor) + ", which is not open for writing");
  struct stat st {};
  if (::fstat(descriptor, &st) == 0 && S_ISDIR(st.st_mode))
    fail(given, 0, "cannot write: it leads to " + descriptor_name(descriptor) + ", which is a directory");
  OutputTarget target;
  target.kind = OutputTarget::Kind::descriptor;
  target.descriptor = descriptor;
  return target;
}

}  // namespace

std::string descriptor_name(int descriptor) {
  if (descriptor == 0) return "standard input";
  if (descriptor == 1) return "standard output";
  if (descriptor == 2) return "standard error";
  return "descriptor " + std::to_string(descriptor);
}

void hold_closed_standard_descriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) >= 0 || errno != EBADF) continue;
    // open() returns the lowest free number: this one, as those below are open.
    const int held = ::open("/dev/null", O_RDONLY | O_NOCTTY);
    if (held < 0) continue;
    if (held != fd) {
      ::close(held);  // not ours to hold (cannot happen: lower ones are open)
      continue;
    }
    g_closed_at_start[fd] = true;
  }
}

bool leads_to_stream(const fs::path& given) {
  try {
    const OutputTarget::Kind kind = resolve_output_target(given).kind;
    return kind == OutputTarget::Kind::device || kind == OutputTarget::Kind::descriptor;
  } catch (const InputError&) {
    return false;
  }
}

OutputTarget resolve_output_target(const fs::path& given) {
  if (given == "-") return open_descriptor(given, STDOUT_FILENO);
  fs::path current = given;
  std::string link_text;  // what the last link followed says, for messages
  for (int links = 0;; ++links) {
    const bool through_link = links > 0;
    const fs::path folder = current.parent_path().empty() ? fs::path(".") : current.parent_path();
    std::error_code ec;
    const fs::path real_folder = fs::canonical(folder, ec);
    if (ec || !fs::is_directory(real_folder, ec)) {
      const std::string why = ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory
                                  ? "': " + ec.message()
                                  : "' does not exist";
      if (through_link)
        fail(given, 0, "cannot write: it is a symbolic link to '" + link_text + "', whose folder '" + folder.string() + why);
      fail(given, 0, "cannot write: folder '" + folder.string() + why);
    }
    const fs::path name = current.filename();
    if (name.empty() || name == "." || name == "..") fail(given, 0, "cannot write: it is a directory");
    if (is_own_descriptor_folder(real_folder) && all_digits(name.string()))
      return open_descriptor(given, std::stoi(name.string()));

    const fs::path here = real_folder / name;
    struct stat st {};
    if (::lstat(here.c_str(), &st) != 0) {
      const int err = errno;
      if (err != ENOENT) fail(given, 0, std::string("cannot write: ") + std::strerror(err));
      // Through a link that leads nowhere yet, the file it names is made
      // (as `>`, oiiotool and tar do), and the link stays.
      if (in_system_folder(real_folder))
        fail(given, 0, "cannot write: no file is made in " + real_folder.string() + ": give a path outside /dev and /proc");
      return {OutputTarget::Kind::new_file, here, -1};
    }
    if (S_ISLNK(st.st_mode)) {
      if (links + 1 > kMaxLinks) fail(given, 0, "cannot write: a loop of symbolic links (or more than 40 in a row)");
      // As the kernel's fs.protected_symlinks: a link another user planted
      // in a sticky, world-writable folder (/tmp) is not followed.
      struct stat folder_st {};
      if (::stat(real_folder.c_str(), &folder_st) == 0 && (folder_st.st_mode & S_ISVTX) && (folder_st.st_mode & S_IWOTH) &&
          st.st_uid != ::geteuid() && st.st_uid != folder_st.st_uid)
        fail(given, 0, "cannot write: '" + here.string() +
                           "' is another user's symbolic link in a sticky folder, which is not followed (as "
                           "fs.protected_symlinks)");
      std::error_code read_ec;
      const fs::path to = fs::read_symlink(here, read_ec);
      if (read_ec) fail(given, 0, "cannot write: cannot read the symbolic link '" + here.string() + "': " + read_ec.message());
      link_text = to.string();
      current = to.is_absolute() ? to : real_folder / to;
      continue;
    }
    if (S_ISDIR(st.st_mode)) fail(given, 0, "cannot write: it is a directory");
    if (S_ISSOCK(st.st_mode)) fail(given, 0, "cannot write: it is a socket");
    if (S_ISBLK(st.st_mode)) fail(given, 0, "cannot write: it is a block device");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {OutputTarget::Kind::device, here, -1};
    if (in_system_folder(real_folder))
      fail(given, 0, "cannot write: '" + here.string() + "' is a file in " + real_folder.string() +
                         ", which is never replaced: give a path outside /dev and /proc");
    return {OutputTarget::Kind::file, here, -1};
  }
}

}  // namespace kappa
