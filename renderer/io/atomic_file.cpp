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

#include "core/error.h"
#include "renderer/io/output_target.h"

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
  // Where the path leads, links followed and never replaced (output_target.h).
  const OutputTarget where = resolve_output_target(target);
  using Kind = OutputTarget::Kind;
  switch (where.kind) {
    case Kind::descriptor:
      if (kind == OutputKind::image)
        fail(target, 0, "cannot write an image to " + descriptor_name(where.descriptor) + ": give a file name");
      // A copy of the descriptor, so the output stays what it was when the
      // run started.
      m_descriptor = ::fcntl(where.descriptor, F_DUPFD_CLOEXEC, 3);
      if (m_descriptor < 0) fail(target, 0, std::string("cannot write: ") + std::strerror(errno));
      m_direct = true;
      m_committed = true;  // nothing to remove
      return;
    case Kind::device:
      if (kind == OutputKind::image) fail(target, 0, "cannot write an image to a device or FIFO: give a file name");
      // Written as it is: no temporary, no rename over the node.
      m_direct = true;
      m_final = m_temp = where.path;
      m_committed = true;  // nothing to remove
      return;
    case Kind::new_file:
    case Kind::file:
      break;
  }
  m_final = where.path;
  // Same folder as the file written, so the final rename cannot cross file
  // systems; the .exr ending keeps format detection by extension working.
  m_temp = m_final.parent_path() / ("." + m_final.filename().string() + ".kappa-" + std::to_string(::getpid()) +
                                    ".tmp" + m_final.extension().string());
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
  if (m_descriptor >= 0) ::close(m_descriptor);
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
  if (output.descriptor() >= 0) {
    // Written straight to the descriptor: a pipe whose reader went away, or
    // a full disk behind `>> log`, is not the input's fault (exit 1).
    for (std::size_t done = 0; done < text.size();) {
      const ssize_t n = ::write(output.descriptor(), text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw std::runtime_error(output.target().string() + ": cannot write (" + std::strerror(n < 0 ? errno : EIO) + ")");
      done += std::size_t(n);
    }
    return;
  }
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
  if (std::rename(m_temp.c_str(), m_final.c_str()) != 0) fail_output(m_target, "cannot replace", errno);
  m_committed = true;
}

}  // namespace kappa
