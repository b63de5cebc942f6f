// Outputs never lose a byte of anyone's data, whatever fails or ends the
// process: a render whose Nth write, fsync, rename/link or open fails (for
// every N the render makes: tests/fault/fault_shim.c, loaded with
// LD_PRELOAD), one killed by SIGKILL at random moments, and two renders
// writing the same file at once each leave the previous outputs byte for byte
// as they were or the new ones whole, and no temporary behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/io/exr_input.h"
#include "test_util.h"

extern char** environ;

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

/// The render the faults are injected into: an EXR, its report and a PNG
/// preview, in `outputs`, of a copy of the Cornell box in `scene_dir`.
std::vector<std::string> render_args(const fs::path& scene_dir, const fs::path& outputs, int spp) {
  return {"render", (scene_dir / "scene.json").string(), "--spp", std::to_string(spp), "--width", "16", "--height",
          "16", "-q", "--out", (outputs / "image.exr").string(), "--report", (outputs / "report.json").string(),
          "--preview", (outputs / "preview.png").string()};
}

/// The same render without its preview, which loads OpenImageIO (1 s a run
/// here): for the tests that run it often.
std::vector<std::string> quick_render_args(const fs::path& scene_dir, const fs::path& outputs, int spp) {
  std::vector<std::string> args = render_args(scene_dir, outputs, spp);
  args.resize(args.size() - 2);
  return args;
}

const std::vector<std::string> kOutputs = {"image.exr", "report.json", "preview.png"};

/// The names in `folder`, sorted.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Whether the output `name` in `outputs` is the old one byte for byte, or
/// a whole new one: an EXR with the new render's pixels, a report that
/// parses with the new spp, a PNG of the right size. Says which in `what`.
bool old_or_whole(const fs::path& outputs, const std::string& name, const std::string& old_bytes,
                  const ReferenceImage& new_image, int new_spp, std::string& what, const fs::path& read_from = {}) {
  const fs::path file = read_from.empty() ? outputs / name : read_from;
  const std::string bytes = read_file(file);
  if (bytes == old_bytes) {
    what = "old";
    return true;
  }
  what = "new";
  try {
    if (name == "image.exr") return read_reference(file).rgb == new_image.rgb;
    if (name == "report.json") return nlohmann::json::parse(bytes).at("render").at("spp").get<int>() == new_spp;
    // A PNG: its signature, and its end chunk (IEND and CRC) last.
    return bytes.size() > 20 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 &&
           bytes.compare(bytes.size() - 12, 12, std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12)) == 0;
  } catch (const std::exception& e) {
    what = std::string("unreadable: ") + e.what();
    return false;
  }
}

struct Outcome {
  int runs = 0, faults = 0, lost = 0, left_behind = 0, crashed = 0;
  /// Whole new outputs under the killed process's temporary name: killed in
  /// the instant between the link and the rename that replaces a file
  /// (renderer/io/atomic_file.cpp: Linux cannot link over a name).
  int named_in_the_instant = 0;
  std::map<int, int> exit_codes;
};

class FaultInjection : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::copy(assets_dir() / "cornell-box", tmp / "scene", fs::copy_options::recursive);
    // The outputs on a memory file system where there is one: each render
    // syncs its three outputs, 0.3 s each on this project's disks.
    if (fs::is_directory("/dev/shm")) {
      out = "/dev/shm/kappa-fault-" + std::to_string(::getpid());
      fs::create_directory(out);
      fs::create_symlink(out, tmp / "out");
    } else {
      fs::create_directory(tmp / "out");
    }
    // The previous outputs: a render at 1 spp.
    const RunResult first = run_kappa(render_args(tmp / "scene", tmp / "out", 1));
    ASSERT_EQ(first.exit_code, 0) << first.std_err;
    for (const auto& name : kOutputs) old_bytes[name] = read_file(tmp / "out" / name);
    // The new render's pixels, at 2 spp, made elsewhere.
    fs::create_directory(tmp / "expected");
    const RunResult second = run_kappa(render_args(tmp / "scene", tmp / "expected", 2));
    ASSERT_EQ(second.exit_code, 0) << second.std_err;
    new_image = read_reference(tmp / "expected" / "image.exr");
  }

  /// Puts the old outputs back and removes anything else in the folder.
  void restore() {
    for (const auto& name : names_in(tmp / "out"))
      if (!old_bytes.count(name)) fs::remove_all(tmp / "out" / name);
    for (const auto& [name, bytes] : old_bytes) write_file(tmp / "out" / name, bytes);
  }

  /// The output a name beside the outputs stands for, if it is the
  /// temporary name `killed` (a process killed by a signal) would give it
  /// (.kappa-PID-N.tmp.EXT), else "".
  static std::string output_named_by(const std::string& name, pid_t killed) {
    const std::string prefix = ".kappa-" + std::to_string(killed) + "-";
    if (killed <= 0 || name.rfind(prefix, 0) != 0) return "";
    for (const auto& output : kOutputs)
      if (name.ends_with(".tmp" + fs::path(output).extension().string())) return output;
    return "";
  }

  /// Checks the folder after a run that ended with `code` (or was killed:
  /// `killed` its pid), into `outcome`.
  void check(int code, const std::string& label, Outcome& outcome, pid_t killed = 0) {
    ++outcome.runs;
    ++outcome.exit_codes[code];
    if (code > 2) {
      ++outcome.crashed;
      ADD_FAILURE() << label << ": exit " << code;
    }
    std::vector<std::string> names = names_in(tmp / "out");
    // Killed between the link and the rename: a whole new output under the
    // temporary name is the only thing a kill may leave.
    std::erase_if(names, [&](const std::string& name) {
      const std::string output = output_named_by(name, killed);
      std::string what;
      if (output.empty() ||
          !old_or_whole(tmp / "out", output, old_bytes[output], new_image, 2, what, tmp / "out" / name) ||
          what != "new")
        return false;
      ++outcome.named_in_the_instant;
      return true;
    });
    if (names != std::vector<std::string>{"image.exr", "preview.png", "report.json"}) {
      ++outcome.left_behind;
      std::string listing;
      for (const auto& n : names) listing += n + " ";
      ADD_FAILURE() << label << ": the folder holds " << listing;
    }
    for (const auto& name : kOutputs) {
      std::string what;
      if (!fs::exists(tmp / "out" / name) || !old_or_whole(tmp / "out", name, old_bytes[name], new_image, 2, what)) {
        ++outcome.lost;
        ADD_FAILURE() << label << ": " << name << " is neither the old one nor a whole new one (" << what << ")";
      } else if (code != 0 && what == "new" && name == "image.exr") {
        // A failed run may still have put some outputs in place before the
        // failure (they are whole); the report says which failed.
      }
    }
    restore();
  }

  void TearDown() override {
    if (!out.empty()) fs::remove_all(out);
  }

  Outcome inject_every_fault(const std::vector<std::string>& more, const std::set<std::string>& families);

  TempDir tmp;
  fs::path out;  ///< the outputs' folder in /dev/shm, or empty
  std::map<std::string, std::string> old_bytes;
  ReferenceImage new_image;
};

/// The shim loaded, with `more` settings (KAPPA_FAULT=..., ...).
std::vector<std::string> with_shim(std::vector<std::string> more) {
  std::vector<std::string> env = {"env", std::string("LD_PRELOAD=") + KAPPA_FAULT_SHIM};
  env.insert(env.end(), more.begin(), more.end());
  return env;
}

/// The calls of each family a render makes, counted by the shim.
std::map<std::string, long> count_calls(const std::vector<std::string>& args, const fs::path& counts,
                                        std::vector<std::string> more) {
  more.insert(more.end(), {"KAPPA_FAULT=count", "KAPPA_FAULT_COUNTS=" + counts.string()});
  const RunResult r = run_kappa_under(with_shim(more), args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  std::map<std::string, long> n;
  std::istringstream in(read_file(counts));
  std::string family;
  long calls = 0;
  while (in >> family >> calls) n[family] = calls;
  return n;
}

/// Fails each call of each of `families` in turn, with `more` settings.
Outcome FaultInjection::inject_every_fault(const std::vector<std::string>& more, const std::set<std::string>& families) {
  const std::vector<std::string> args = render_args(tmp / "scene", tmp / "out", 2);
  const std::map<std::string, long> calls = count_calls(args, tmp / "counts", more);
  EXPECT_EQ(calls.size(), 4u);
  restore();
  Outcome outcome;
  for (const auto& [family, n] : calls) {
    if (!families.count(family)) continue;
    EXPECT_GT(n, 0) << family << " is never called: the shim sees nothing";
    for (long k = 1; k <= n; ++k) {
      const std::string plan = family + ":" + std::to_string(k);
      std::vector<std::string> settings = more;
      settings.push_back("KAPPA_FAULT=" + plan);
      const RunResult r = run_kappa_under(with_shim(settings), args);
      ++outcome.faults;
      check(r.exit_code, plan + " (" + r.std_err.substr(0, 300) + ")", outcome);
    }
  }
  std::printf("fault injection%s: %d runs, %d faults injected (", more.empty() ? "" : " (no O_TMPFILE)", outcome.runs,
              outcome.faults);
  for (const auto& [family, n] : calls)
    if (families.count(family)) std::printf(" %s %ld", family.c_str(), n);
  std::printf(" ), outputs lost %d, temporaries left %d, crashes %d; exit codes:", outcome.lost, outcome.left_behind,
              outcome.crashed);
  for (const auto& [code, times] : outcome.exit_codes) std::printf(" %d x%d", code, times);
  std::printf("\n");
  EXPECT_EQ(outcome.lost, 0);
  EXPECT_EQ(outcome.left_behind, 0);
  // Some faults must end the run (a failed write of an output cannot pass).
  EXPECT_GT(outcome.runs - outcome.exit_codes[0], 0);
  return outcome;
}

TEST_F(FaultInjection, EveryFailedCallOfARenderLeavesTheOldOutputsOrWholeNewOnes) {
  inject_every_fault({}, {"write", "fsync", "rename", "open"});
}

// Where the file system has no unnamed files, the named temporaries take
// their place and are removed on every failure.
TEST_F(FaultInjection, WithoutUnnamedFilesEveryFailedWriteSyncOrRenameLeavesNothingBehind) {
  inject_every_fault({"KAPPA_FAULT_NO_TMPFILE=1"}, {"write", "fsync", "rename"});
}

TEST_F(FaultInjection, ARenderKilledAtAnyMomentLeavesTheOldOutputsOrWholeNewOnes) {
  std::vector<std::string> args = quick_render_args(tmp / "scene", tmp / "out", 2);
  std::vector<std::string> argv_strings = {KAPPA_BINARY};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  // How long a whole run takes (the shortest of three: the machine's speed
  // drifts), to spread the kills over it.
  double run_s = 1e9;
  for (int i = 0; i < 3; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(run_kappa(args).exit_code, 0);
    run_s = std::min(run_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  restore();
  std::mt19937 rng(49);
  std::uniform_real_distribution<double> moment(0.0, 1.2 * run_s);
  Outcome outcome;
  int killed = 0;
  for (int i = 0; i < 50; ++i) {
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, KAPPA_BINARY, nullptr, nullptr, argv.data(), environ), 0);
    const double at = moment(rng);
    std::this_thread::sleep_for(std::chrono::duration<double>(at));
    ::kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    killed += WIFSIGNALED(status);
    check(WIFEXITED(status) ? WEXITSTATUS(status) : 0, "killed at " + std::to_string(at) + " s", outcome,
          WIFSIGNALED(status) ? pid : 0);
  }
  std::printf("SIGKILL: %d runs (%.3f s each), %d killed before they ended, outputs lost %d, temporaries left %d, "
              "whole outputs left under their temporary name %d\n",
              outcome.runs, run_s, killed, outcome.lost, outcome.left_behind, outcome.named_in_the_instant);
  // The instant is a link and a rename, microseconds of an 0.1 s run: more
  // than a few such names would mean a wider window (a name given before
  // the file is whole fails above, as a temporary left).
  EXPECT_LE(outcome.named_in_the_instant, 2);
  EXPECT_GT(killed, 5) << "the kills came too late to test anything";
}

TEST_F(FaultInjection, TwoRendersWritingTheSameFilesAtOnceLeaveWholeOnes) {
  const std::string args = [&] {
    std::string s = std::string(KAPPA_BINARY);
    for (const auto& a : quick_render_args(tmp / "scene", tmp / "out", 2)) s += " '" + a + "'";
    return s;
  }();
  // Both waited for, whatever the first's end.
  write_file(tmp / "two.sh", args + " & a=$!\n" + args + " & b=$!\nwait $a; ra=$?\nwait $b; rb=$?\nexit $((ra | rb))\n");
  Outcome outcome;
  for (int i = 0; i < 5; ++i) {
    const int status = std::system(("bash '" + (tmp / "two.sh").string() + "' 2>/dev/null").c_str());
    check(WIFEXITED(status) ? WEXITSTATUS(status) : 128, "two at once", outcome);
  }
  EXPECT_EQ(outcome.exit_codes[0], 5);
}

}  // namespace
}  // namespace kappa::test
