// Where an output path leads (renderer/io/output_target.h), on links this
// test makes in its own folder: the machine's /dev/stdout is never used.
#include "renderer/io/output_target.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "renderer/io/atomic_file.h"
#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;
using Kind = OutputTarget::Kind;

/// The message resolve_output_target refuses `path` with ("" if it does not).
std::string refusal(const fs::path& path) {
  try {
    resolve_output_target(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A pipe whose ends close with the test.
struct Pipe {
  int fds[2] = {-1, -1};
  Pipe() { EXPECT_EQ(::pipe(fds), 0); }
  ~Pipe() {
    for (int fd : fds)
      if (fd >= 0) ::close(fd);
  }
  std::string read_all() {
    ::close(fds[1]);
    fds[1] = -1;
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, std::size_t(n));
    return text;
  }
};

TEST(OutputTarget, PlainPathsAreNewOrExistingFilesInTheirRealFolder) {
  TempDir tmp;
  const fs::path real = fs::canonical(tmp.path());
  const OutputTarget fresh = resolve_output_target(tmp / "x.json");
  EXPECT_EQ(fresh.kind, Kind::new_file);
  EXPECT_EQ(fresh.path, real / "x.json");
  write_file(tmp / "x.json", "old");
  EXPECT_EQ(resolve_output_target(tmp / "x.json").kind, Kind::file);
  EXPECT_NE(refusal(tmp / "missing" / "x.json").find("folder '" + (tmp / "missing").string() + "' does not exist"),
            std::string::npos);
  EXPECT_NE(refusal(tmp.path()).find("it is a directory"), std::string::npos);
  EXPECT_NE(refusal(tmp.path() / "").find("it is a directory"), std::string::npos);
}

TEST(OutputTarget, LinksAreFollowedToTheFileTheyLeadTo) {
  TempDir tmp;
  const fs::path real = fs::canonical(tmp.path());
  fs::create_directory(tmp / "sub");
  write_file(tmp / "data.json", "old");
  // A relative link is read from its own folder, not the working directory.
  fs::create_symlink("../data.json", tmp / "sub" / "rel.json");
  fs::create_symlink(tmp / "sub" / "rel.json", tmp / "chain.json");
  for (const fs::path& link : {tmp / "sub" / "rel.json", tmp / "chain.json"}) {
    SCOPED_TRACE(link);
    const OutputTarget t = resolve_output_target(link);
    EXPECT_EQ(t.kind, Kind::file);
    EXPECT_EQ(t.path, real / "data.json");
  }
  // A link in the folder part too.
  fs::create_directory_symlink(tmp / "sub", tmp / "sublink");
  EXPECT_EQ(resolve_output_target(tmp / "sublink" / "new.json").path, real / "sub" / "new.json");
  // To a FIFO or device: written in place.
  ASSERT_EQ(::mkfifo((tmp / "f").c_str(), 0600), 0);
  fs::create_symlink(tmp / "f", tmp / "to_fifo");
  EXPECT_EQ(resolve_output_target(tmp / "to_fifo").kind, Kind::device);
  fs::create_symlink("/dev/null", tmp / "to_null");
  EXPECT_EQ(resolve_output_target(tmp / "to_null").kind, Kind::device);
  fs::create_directory_symlink(tmp / "sub", tmp / "to_dir");
  EXPECT_NE(refusal(tmp / "to_dir").find("it is a directory"), std::string::npos);
}

TEST(OutputTarget, ALinkToAFileNotYetMadeIsWrittenThroughButLoopsAreRefused) {
  TempDir tmp;
  fs::create_symlink("nothing.json", tmp / "dangling.json");
  fs::create_symlink(tmp / "gone" / "x.json", tmp / "no_folder.json");
  fs::create_symlink("b", tmp / "a");
  fs::create_symlink("a", tmp / "b");
  fs::create_symlink("self", tmp / "self");
  // As the shell's `>` and oiiotool: the file the link names is made.
  const OutputTarget through = resolve_output_target(tmp / "dangling.json");
  EXPECT_EQ(through.kind, Kind::new_file);
  EXPECT_EQ(through.path, fs::canonical(tmp.path()) / "nothing.json");
  EXPECT_NE(refusal(tmp / "no_folder.json").find("whose folder"), std::string::npos);
  EXPECT_NE(refusal(tmp / "a").find("a loop of symbolic links"), std::string::npos);
  EXPECT_NE(refusal(tmp / "self").find("a loop of symbolic links"), std::string::npos);
  // A chain of 40 links resolves (Linux's limit); 41 do not.
  write_file(tmp / "end", "");
  fs::path previous = tmp / "end";
  for (int i = 0; i < 41; ++i) {
    const fs::path link = tmp / ("l" + std::to_string(i));
    fs::create_symlink(previous, link);
    previous = link;
  }
  EXPECT_EQ(resolve_output_target(tmp / "l39").kind, Kind::file);
  EXPECT_NE(refusal(tmp / "l40").find("a loop of symbolic links"), std::string::npos);
  // Nothing was made or replaced by resolving.
  for (const char* name : {"dangling.json", "no_folder.json", "a", "b", "self"})
    EXPECT_TRUE(fs::is_symlink(tmp / name)) << name;
  EXPECT_FALSE(fs::exists(tmp / "nothing.json"));
  // Written: the file appears where the link leads, and the link stays.
  {
    AtomicOutput out(tmp / "dangling.json");
    write_and_commit(out, "made");
  }
  EXPECT_TRUE(fs::is_symlink(tmp / "dangling.json"));
  EXPECT_EQ(read_file(tmp / "nothing.json"), "made");
}

TEST(OutputTarget, DescriptorPathsAreTheDescriptorNotTheFileBehindIt) {
  TempDir tmp;
  Pipe pipe;
  const int w = pipe.fds[1];
  fs::create_symlink("/proc/self/fd/" + std::to_string(w), tmp / "out");
  fs::create_symlink("/proc/thread-self/fd/" + std::to_string(w), tmp / "thread_out");
  for (const fs::path& path : {fs::path("/proc/self/fd/" + std::to_string(w)), tmp / "out", tmp / "thread_out"}) {
    SCOPED_TRACE(path);
    const OutputTarget t = resolve_output_target(path);
    EXPECT_EQ(t.kind, Kind::descriptor);
    EXPECT_EQ(t.descriptor, w);
  }
  EXPECT_EQ(resolve_output_target("-").kind, Kind::descriptor);
  EXPECT_EQ(resolve_output_target("-").descriptor, 1);
  // A regular file behind a descriptor is still the descriptor: a report
  // into `>> log` must append, not rename a new file over the log.
  write_file(tmp / "log", "first\n");
  const int log = ::open((tmp / "log").c_str(), O_WRONLY | O_APPEND);
  ASSERT_GE(log, 0);
  fs::create_symlink("/proc/self/fd/" + std::to_string(log), tmp / "to_log");
  EXPECT_EQ(resolve_output_target(tmp / "to_log").kind, Kind::descriptor);
  ::close(log);
}

TEST(OutputTarget, ClosedAndReadOnlyDescriptorsAreRefused) {
  TempDir tmp;
  int closed = -1;
  {
    Pipe pipe;
    closed = pipe.fds[1];
  }
  fs::create_symlink("/proc/self/fd/" + std::to_string(closed), tmp / "closed");
  const std::string why = refusal(tmp / "closed");
  EXPECT_NE(why.find(tmp.path().string() + "/closed: cannot write: it leads to descriptor " + std::to_string(closed) +
                     ", which is closed"),
            std::string::npos)
      << why;
  EXPECT_TRUE(fs::is_symlink(tmp / "closed"));
  Pipe pipe;
  fs::create_symlink("/proc/self/fd/" + std::to_string(pipe.fds[0]), tmp / "read_end");
  EXPECT_NE(refusal(tmp / "read_end").find("which is not open for writing"), std::string::npos);
  EXPECT_EQ(descriptor_name(1), "standard output");
  EXPECT_EQ(descriptor_name(2), "standard error");
}

TEST(OutputTarget, NoFileIsMadeOrReplacedInDevOrProc) {
  EXPECT_NE(refusal("/dev/kappa-output-target-test.json").find("no file is made in /dev"), std::string::npos);
  EXPECT_NE(refusal("/proc/kappa-output-target-test.json").find("no file is made in /proc"), std::string::npos);
  // /proc/self/status is a regular file in /proc.
  EXPECT_NE(refusal("/proc/self/status").find("which is never replaced"), std::string::npos);
  EXPECT_FALSE(fs::exists("/dev/kappa-output-target-test.json"));
  // /dev/shm is a memory file system like any other folder.
  if (fs::is_directory("/dev/shm")) {
    EXPECT_EQ(refusal("/dev/shm/kappa-output-target-test.json"), "");
  }
}

TEST(OutputTarget, AReportThroughALinkIsWrittenThroughAndTheLinkStays) {
  TempDir tmp;
  write_file(tmp / "data.json", "old");
  fs::create_symlink("data.json", tmp / "link.json");
  {
    AtomicOutput out(tmp / "link.json");
    write_and_commit(out, "new");
  }
  EXPECT_TRUE(fs::is_symlink(tmp / "link.json"));
  EXPECT_EQ(read_file(tmp / "data.json"), "new");
  // Through a descriptor link: into the pipe, the link untouched, nothing
  // left in the folder.
  Pipe pipe;
  fs::create_symlink("/proc/self/fd/" + std::to_string(pipe.fds[1]), tmp / "pipe_link");
  {
    AtomicOutput out(tmp / "pipe_link");
    EXPECT_TRUE(out.direct());
    write_and_commit(out, "through the pipe");
  }
  EXPECT_EQ(pipe.read_all(), "through the pipe");
  EXPECT_TRUE(fs::is_symlink(tmp / "pipe_link"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(tmp.path())) ++entries;
  EXPECT_EQ(entries, 3u);  // data.json, link.json, pipe_link
  // An image for a descriptor is made whole in memory and sent at commit:
  // nothing reaches the pipe from a render that fails.
  Pipe image_pipe;
  {
    AtomicOutput out("/proc/self/fd/" + std::to_string(image_pipe.fds[1]), OutputKind::image);
    EXPECT_FALSE(out.direct());
    write_file(out.temp_path(), "an image");
    AtomicOutput failed("/proc/self/fd/" + std::to_string(image_pipe.fds[1]), OutputKind::image);
    write_file(failed.temp_path(), "never sent");
    out.commit();
  }
  EXPECT_EQ(image_pipe.read_all(), "an image");
}

/// The names in `folder`.
std::vector<std::string> entries_of(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicOutput, TheOutputIsMadeWithoutANameUntilItIsCommitted) {
  TempDir tmp;
  write_file(tmp / "image.exr", "old");
  {
    AtomicOutput out(tmp / "image.exr", OutputKind::image);
    write_file(out.temp_path(), "new");
    // Nothing in the folder but the old file while the output is made, so
    // that a process killed now (SIGKILL included) leaves nothing behind.
    EXPECT_EQ(entries_of(tmp.path()), std::vector<std::string>{"image.exr"});
    EXPECT_EQ(read_file(tmp / "image.exr"), "old");
    out.commit();
  }
  EXPECT_EQ(entries_of(tmp.path()), std::vector<std::string>{"image.exr"});
  EXPECT_EQ(read_file(tmp / "image.exr"), "new");
  {
    AtomicOutput abandoned(tmp / "image.exr", OutputKind::image);
    write_file(abandoned.temp_path(), "abandoned");
  }
  EXPECT_EQ(entries_of(tmp.path()), std::vector<std::string>{"image.exr"});
  EXPECT_EQ(read_file(tmp / "image.exr"), "new");
}

TEST(AtomicOutput, NamesUpToNameMaxAreWritten) {
  TempDir tmp;
  for (std::size_t length : {250u, 255u}) {
    const std::string name = std::string(length - 4, 'a') + ".exr";
    {
      AtomicOutput out(tmp / name, OutputKind::image);
      write_file(out.temp_path(), "whole");
      out.commit();
    }
    EXPECT_EQ(read_file(tmp / name), "whole") << length;
  }
  // The temporary name beside any name is short and hidden, and keeps a short extension.
  const std::string temporary = temporary_name(std::string(251, 'a') + ".exr", 4000000000u);
  EXPECT_LE(temporary.size(), 48u) << temporary;
  EXPECT_EQ(temporary.front(), '.');
  EXPECT_EQ(fs::path(temporary).extension(), ".exr");
  EXPECT_EQ(fs::path(temporary_name("x." + std::string(40, 'e'), 1)).extension(), ".tmp");
}

TEST(OutputTarget, AnotherUsersLinkInAStickyFolderIsNotFollowed) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to make a link of another user";
  TempDir tmp;
  const fs::path sticky = tmp / "sticky";
  fs::create_directory(sticky);
  ::chmod(sticky.c_str(), 01777);
  fs::create_symlink(tmp / "victim.exr", sticky / "planted.exr");
  ASSERT_EQ(::lchown((sticky / "planted.exr").c_str(), 1234, 1234), 0);
  EXPECT_NE(refusal(sticky / "planted.exr").find("is another user's symbolic link in a sticky folder"), std::string::npos)
      << refusal(sticky / "planted.exr");
  // One's own link there is followed.
  fs::create_symlink(tmp / "mine.exr", sticky / "mine.exr");
  EXPECT_EQ(refusal(sticky / "mine.exr"), "");
}

TEST(AtomicOutput, AFileThatCouldNotBeReplacedIsRefusedBeforeTheWork) {
  // A file in a sticky folder that belongs to another user: only checked
  // for a user without root's override, so the test runs the check as one.
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to make a file of another user";
  TempDir tmp;
  const fs::path sticky = tmp / "sticky";
  fs::create_directory(sticky);
  ::chmod(sticky.c_str(), 01777);
  write_file(sticky / "theirs.exr", "theirs");
  ASSERT_EQ(::chown((sticky / "theirs.exr").c_str(), 1234, 1234), 0);
  ::chmod((sticky / "theirs.exr").c_str(), 0666);
  const pid_t child = ::fork();
  if (child == 0) {
    if (::setgid(4321) != 0 || ::setuid(4321) != 0) ::_exit(3);
    try {
      AtomicOutput out(sticky / "theirs.exr", OutputKind::image);
      ::_exit(4);  // accepted
    } catch (const InputError& e) {
      ::_exit(std::string(e.what()).find("belongs to another user in a sticky folder") != std::string::npos ? 0 : 5);
    }
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: cannot change user, 4: accepted, 5: another message";
  EXPECT_EQ(read_file(sticky / "theirs.exr"), "theirs");
}

}  // namespace
}  // namespace kappa::test
