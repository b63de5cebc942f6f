#include "renderer/io/atomic_file.h"

#include <fcntl.h>
#include <linux/fs.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>

#include "core/error.h"
#include "renderer/io/output_target.h"

namespace kappa {
namespace {

namespace fs = std::filesystem;

// The signal handler may only call async-signal-safe functions, so the paths
// to remove live in fixed buffers, published through atomic flags.
constexpr int kSlots = 8;
constexpr std::size_t kPathMax = 4096;
std::array<char[kPathMax], kSlots> g_paths;
std::array<std::atomic<bool>, kSlots> g_claimed{};  ///< slot taken
std::array<std::atomic<bool>, kSlots> g_ready{};    ///< path written
std::once_flag g_handlers_installed;

std::atomic<bool> g_holding{false};
std::atomic<int> g_pending{0};  ///< a signal that came while held
std::atomic<unsigned> g_sequence{0};  ///< tells this process's temporaries apart

extern "C" void remove_temporaries_and_exit(int sig) {
  if (g_holding.load()) {
    g_pending.store(sig);
    return;
  }
  for (int i = 0; i < kSlots; ++i)
    if (g_ready[i].load()) ::unlink(g_paths[i]);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal the parent ignores (nohup, a background job's Ctrl-C) stays ignored.
    struct sigaction old {};
    ::sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_exit;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

int claim_slot(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    if (g_claimed[i].exchange(true)) continue;
    std::strcpy(g_paths[i], path.c_str());
    g_ready[i].store(true);  // only now may the handler read the path
    return i;
  }
  return -1;
}

void release_slot(int i) {
  g_ready[i].store(false);
  g_claimed[i].store(false);
}

/// The path of this process's descriptor `fd` in /proc, by process id, so
/// that a child process (the plot script) opens the same file.
fs::path proc_path(int fd) { return "/proc/" + std::to_string(::getpid()) + "/fd/" + std::to_string(fd); }

/// Whether /proc shows this process's descriptors (it does unless /proc is
/// not mounted): unnamed files are written through it.
bool proc_available() { return ::access(("/proc/" + std::to_string(::getpid()) + "/fd").c_str(), X_OK) == 0; }

/// `fd` moved above the standard descriptors: with standard output closed,
/// a new file would otherwise become descriptor 1, and a report to
/// /dev/stdout would be written into it. Returns -1 (errno set) if `fd` was.
int above_standard_descriptors(int fd) {
  if (fd < 0 || fd > 2) return fd;
  const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
  const int err = errno;
  ::close(fd);
  errno = err;
  return moved;
}

/// Writes all of `bytes` to `fd`; false with errno set on failure.
bool write_all(int fd, const char* bytes, std::size_t size) {
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    done += std::size_t(n);
  }
  return true;
}

/// Refuses, before any work, a file that rename() could not replace: one in
/// a sticky folder (/tmp) that belongs to another user, or one marked
/// immutable or append-only (chattr +i, +a).
void refuse_unreplaceable(const fs::path& given, const fs::path& file) {
  const fs::path folder = file.parent_path();
  struct stat file_st {}, folder_st {};
  if (::stat(file.c_str(), &file_st) != 0 || ::stat(folder.c_str(), &folder_st) != 0) return;
  const uid_t me = ::geteuid();
  if ((folder_st.st_mode & S_ISVTX) && me != 0 && file_st.st_uid != me && folder_st.st_uid != me)
    fail(given, 0, "cannot replace it: it belongs to another user in a sticky folder ('" + folder.string() +
                       "', like /tmp), where only its owner may replace it");
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return;  // unreadable: its flags are unknown; the rename will say
  int flags = 0;
  const bool known = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
  ::close(fd);
  if (known && (flags & (FS_IMMUTABLE_FL | FS_APPEND_FL)))
    fail(given, 0, std::string("cannot replace it: it is marked ") +
                       ((flags & FS_IMMUTABLE_FL) ? "immutable (chattr +i)" : "append-only (chattr +a)"));
}

}  // namespace

std::string temporary_name(const fs::path& final_name, unsigned sequence) {
  std::string extension = final_name.extension().string();
  if (extension.size() > 12) extension.clear();
  return ".kappa-" + std::to_string(::getpid()) + "-" + std::to_string(sequence) + ".tmp" + extension;
}

MemoryFile::MemoryFile(const char* name) {
  m_fd = above_standard_descriptors(::memfd_create(name, MFD_CLOEXEC));
  if (m_fd < 0) throw std::runtime_error(std::string("cannot make a file in memory: ") + std::strerror(errno));
  m_path = proc_path(m_fd);
}

MemoryFile::~MemoryFile() {
  if (m_fd >= 0) ::close(m_fd);
}

AtomicOutput::AtomicOutput(const fs::path& target, OutputKind kind) : m_target(target) {
  std::call_once(g_handlers_installed, install_handlers);
  // Where the path leads, links followed and never replaced (output_target.h).
  const OutputTarget where = resolve_output_target(target);
  using Kind = OutputTarget::Kind;
  switch (where.kind) {
    case Kind::descriptor:
      if (kind == OutputKind::image && !proc_available())
        fail(target, 0, "cannot write an image to a device, FIFO or descriptor without /proc: give a file name");
      // A copy of the descriptor, so the output stays what it was when the
      // run started.
      m_descriptor = ::fcntl(where.descriptor, F_DUPFD_CLOEXEC, 3);
      if (m_descriptor < 0) fail(target, 0, std::string("cannot write: ") + std::strerror(errno));
      break;
    case Kind::device:
      m_final = where.path;
      break;
    case Kind::file:
      refuse_unreplaceable(target, where.path);
      [[fallthrough]];
    case Kind::new_file:
      m_final = where.path;
      m_new = where.kind == Kind::new_file;
      stage_in_folder(m_final.parent_path());
      return;
  }
  if (kind == OutputKind::text) {
    // Written as it comes: no temporary, no rename over the node.
    m_direct = true;
    m_temp = m_final;  // empty for a descriptor
  } else {
    // Made whole in memory, then copied: a render that fails sends nothing.
    if (!proc_available())
      fail(target, 0, "cannot write an image to a device, FIFO or descriptor without /proc: give a file name");
    try {
      m_memory = std::make_unique<MemoryFile>("kappa-image");
    } catch (...) {
      if (m_descriptor >= 0) ::close(m_descriptor);  // the destructor does not run for a throwing constructor
      throw;
    }
    m_temp = m_memory->path();
  }
  m_committed = true;  // nothing to remove
}

void AtomicOutput::stage_in_folder(const fs::path& folder) {
  // Unnamed first: nothing to leave behind, whatever ends the process.
  if (proc_available()) {
    m_staging = above_standard_descriptors(::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644));
    if (m_staging >= 0) {
      m_unnamed = true;
      m_temp = proc_path(m_staging);
      return;
    }
    const int err = errno;
    // Refused for a reason a named file would meet as well.
    if (err != EOPNOTSUPP && err != EISDIR && err != EINVAL && err != ENOENT)
      fail(m_target, 0, std::string("cannot write: ") + std::strerror(err));
  }
  // A named temporary in the same folder, so the final rename cannot cross
  // file systems; registered for the signal handler before it exists, so no
  // interrupt can leave it behind.
  // A name left by a process of the same id that was killed is skipped.
  for (int attempt = 0;; ++attempt) {
    m_named = folder / temporary_name(m_final.filename(), g_sequence++);
    m_slot = claim_slot(m_named.string());
    if (m_slot < 0) fail(m_target, 0, "cannot write: path too long or too many outputs at once");
    const int fd = ::open(m_named.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    const int err = errno;
    if (fd >= 0) {
      m_staging = above_standard_descriptors(fd);
      if (m_staging >= 0) break;
      ::unlink(m_named.c_str());
    }
    release_slot(m_slot);
    m_slot = -1;
    if (fd >= 0 || err != EEXIST || attempt > 100) {
      m_committed = true;  // nothing to remove
      fail(m_target, 0, std::string("cannot write: ") + std::strerror(fd >= 0 ? errno : err));
    }
  }
  m_temp = m_named;
}

AtomicOutput::~AtomicOutput() {
  if (m_descriptor >= 0) ::close(m_descriptor);
  if (m_staging >= 0) ::close(m_staging);
  if (!m_committed && !m_named.empty()) ::unlink(m_named.c_str());
  if (m_slot >= 0) release_slot(m_slot);
}

std::unique_ptr<AtomicOutput> optional_output(const fs::path& target, OutputKind kind) {
  return target.empty() ? nullptr : std::make_unique<AtomicOutput>(target, kind);
}

SignalsHeld::SignalsHeld() { g_holding.store(true); }

SignalsHeld::~SignalsHeld() {
  g_holding.store(false);
  if (const int sig = g_pending.exchange(0)) remove_temporaries_and_exit(sig);
}

void write_and_commit(AtomicOutput& output, const std::string& text) {
  write_temporary(output, text);
  output.commit();
}

void write_temporary(AtomicOutput& output, const std::string& text) {
  if (output.descriptor() >= 0) {
    // Written straight to the descriptor: a pipe whose reader went away, or
    // a full disk behind `>> log`, is not the input's fault (exit 1).
    if (!write_all(output.descriptor(), text.data(), text.size())) fail_output(output.target(), "cannot write", errno);
    return;
  }
  std::ofstream out(output.temp_path(), std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  if (!out) {
    // A device or pipe that fails mid-way (a reader that went away), like a
    // full disk, is not the input's fault: exit 1.
    fail_output(output.target(), "cannot write", errno);
  }
}

void AtomicOutput::copy_staged_to_device() {
  int to = m_descriptor;
  if (to < 0) {
    // A FIFO waits here for its reader, as `cat image > fifo` would.
    to = ::open(m_final.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (to < 0) fail_output(m_target, "cannot write", errno);
  }
  std::array<char, 1 << 16> buffer;
  const int from = m_memory->descriptor();
  bool ok = true;
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(from, buffer.data(), buffer.size(), at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = n == 0;
      break;
    }
    if (!write_all(to, buffer.data(), std::size_t(n))) {
      ok = false;
      break;
    }
    at += n;
  }
  const int err = errno;
  if (to != m_descriptor) ::close(to);
  // A device or pipe that fails (a reader gone, /dev/full) is not the
  // input's fault: exit 1.
  if (!ok) fail_output(m_target, "cannot write", err);
}

void AtomicOutput::commit() {
  if (m_direct) return;  // already written in place
  if (m_memory) {
    copy_staged_to_device();
    return;
  }
  // On disk before it takes the target's name, so that a crash right after
  // cannot leave an empty file there. A write the kernel took but could not
  // place (ENOSPC or EDQUOT under delayed allocation, EIO, a network file
  // system's quota) shows only here: refused, the temporary removed.
  if (::fsync(m_staging) != 0 && errno != EINVAL)  // EINVAL: cannot sync, not a failed write
    fail_output(m_target, "cannot write", errno);
  if (m_unnamed && m_new) {
    // Nothing there: the file gets its name at once, atomically, and a
    // process killed now leaves nothing else. Something that appeared
    // meanwhile is replaced as below.
    if (::linkat(AT_FDCWD, proc_path(m_staging).c_str(), AT_FDCWD, m_final.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      m_committed = true;
      return;
    }
    if (errno != EEXIST) fail_output(m_target, "cannot write", errno);
  }
  if (m_unnamed) {
    // A name beside the target for an instant, then the rename: linkat()
    // cannot replace a file, rename() needs a name.
    for (int attempt = 0;; ++attempt) {
      m_named = m_final.parent_path() / temporary_name(m_final.filename(), g_sequence++);
      m_slot = claim_slot(m_named.string());
      if (m_slot < 0) fail_output(m_target, "cannot write: path too long or too many outputs at once", 0);
      if (::linkat(AT_FDCWD, proc_path(m_staging).c_str(), AT_FDCWD, m_named.c_str(), AT_SYMLINK_FOLLOW) == 0) break;
      const int err = errno;
      release_slot(m_slot);
      m_slot = -1;
      m_named.clear();
      if (err != EEXIST || attempt > 100) fail_output(m_target, "cannot write", err);
    }
  }
  if (std::rename(m_named.c_str(), m_final.c_str()) != 0) fail_output(m_target, "cannot replace", errno);
  m_committed = true;
}

}  // namespace kappa
