#include "renderer/io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>

#include "renderer/util/error.h"

namespace kappa {
namespace {

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

}  // namespace

AtomicOutput::AtomicOutput(const std::filesystem::path& target, OutputKind kind) : m_target(target) {
  std::call_once(g_handlers_installed, install_handlers);
  std::error_code ec;
  // A link is written through, never replaced: the temporary goes beside the
  // file it points to (/dev/stdout -> /proc/self/fd/1 -> a file must not
  // become a regular file in /dev).
  if (std::filesystem::is_symlink(target, ec)) {
    const std::filesystem::path real = std::filesystem::weakly_canonical(target, ec);
    if (!ec && !real.empty()) m_target = real;
  }
  const auto status = std::filesystem::status(target, ec);  // follows links
  using std::filesystem::file_type;
  switch (status.type()) {
    case file_type::directory: fail(target, 0, "cannot write: it is a directory");
    case file_type::socket: fail(target, 0, "cannot write: it is a socket");
    case file_type::block: fail(target, 0, "cannot write: it is a block device");
    case file_type::character:
    case file_type::fifo:
      if (kind == OutputKind::image) fail(target, 0, "cannot write an image to a device or FIFO: give a file name");
      // Written as it is: no temporary, no rename over the node.
      m_direct = true;
      m_target = m_temp = target;
      m_committed = true;  // nothing to remove
      return;
    default:
      break;
  }
  const std::filesystem::path dir = m_target.parent_path().empty() ? "." : m_target.parent_path();
  if (!std::filesystem::is_directory(dir, ec)) {
    // A folder that cannot be looked into (EACCES) is not one that is missing.
    if (ec && ec != std::errc::no_such_file_or_directory)
      fail(target, 0, "cannot write: folder '" + dir.string() + "': " + ec.message());
    fail(target, 0, "cannot write: folder '" + dir.string() + "' does not exist");
  }
  // Same folder as the target, so the final rename cannot cross file systems;
  // the .exr ending keeps format detection by extension working.
  m_temp = dir / ("." + m_target.filename().string() + ".kappa-" + std::to_string(::getpid()) + ".tmp" +
                  m_target.extension().string());
  // Registered for the signal handler before it exists, so no interrupt can
  // leave it behind.
  m_slot = claim_slot(m_temp.string());
  if (m_slot < 0) fail(target, 0, "cannot write: path too long or too many outputs at once");
  const int fd = ::open(m_temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    const int err = errno;
    release_slot(m_slot);
    m_slot = -1;
    m_committed = true;  // nothing to remove
    fail(target, 0, std::string("cannot write: ") + std::strerror(err));
  }
  ::close(fd);
}

AtomicOutput::~AtomicOutput() {
  if (m_direct) return;
  if (!m_committed) ::unlink(m_temp.c_str());
  if (m_slot >= 0) release_slot(m_slot);
}

std::unique_ptr<AtomicOutput> optional_output(const std::filesystem::path& target, OutputKind kind) {
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
  {
    std::ofstream out(output.temp_path(), std::ios::binary);
    out << text;
    out.flush();
    if (!out) {
      // A device or pipe that fails mid-way (a reader that went away) is not
      // the input's fault: an internal error, exit 1.
      const int err = errno;
      if (output.direct()) throw std::runtime_error(output.target().string() + ": cannot write (" + std::strerror(err) + ")");
      fail_output(output.target(), "cannot write", err);
    }
  }
}

void AtomicOutput::commit() {
  if (m_direct) return;  // already written in place
  // On disk before it takes the target's name, so that a crash right after
  // cannot leave an empty file there. A write the kernel took but could not
  // place (ENOSPC or EDQUOT under delayed allocation, EIO, a network file
  // system's quota) shows only here: refused, the temporary removed.
  if (const int fd = ::open(m_temp.c_str(), O_RDONLY); fd >= 0) {
    const int synced = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (synced != 0 && err != EINVAL) fail_output(m_target, "cannot write", err);  // EINVAL: cannot sync, not a failed write
  }
  if (std::rename(m_temp.c_str(), m_target.c_str()) != 0) fail_output(m_target, "cannot replace", errno);
  m_committed = true;
}

}  // namespace kappa
