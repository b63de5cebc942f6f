// Helpers shared by the tests: paths, running the `kappa` binary, and small
// procedural scenes built in memory.
#pragma once

#include <sys/types.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace kappa::test {

inline std::filesystem::path source_dir() { return KAPPA_SOURCE_DIR; }
inline std::filesystem::path assets_dir() { return source_dir() / "assets"; }
/// ../shared/scenes beside the checkout, or empty if a user's clone has none.
inline std::filesystem::path shared_scenes_dir() {
  const auto p = source_dir().parent_path() / "shared" / "scenes";
  return std::filesystem::is_directory(p) ? p : std::filesystem::path();
}

/// KAPPA_TEST_SCALE, in (0, 1] (default 1): the sanitizer suite
/// (tools/test.sh --sanitize) sets 0.25 so that the heaviest tests cast fewer
/// rays. Aborts on any other value, so a typo cannot pass silently.
double test_scale();

/// `n` samples or rays scaled by test_scale(), at least `at_least`.
int scaled(int n, int at_least = 1);

/// How much wider a tolerance set by noise must be at scaled(n) samples than
/// at n: the standard error grows as 1/sqrt(samples).
double noise_widening(int n, int at_least = 1);

/// Bit for bit the same floats (an empty channel equals an empty one: memcmp
/// must not see its null data(), which UBSan reports even for 0 bytes).
bool bitwise_equal(const std::vector<float>& a, const std::vector<float>& b);

/// A fresh empty folder under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return m_path; }
  std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

 private:
  std::filesystem::path m_path;
};

struct RunResult {
  int exit_code = -1;
  std::string std_err;
  std::string std_out;
  std::vector<std::string> err_lines() const;
};

/// Runs build/kappa with `args` (each shell-quoted), stdin from /dev/null,
/// in `working_dir` when given (for relative paths such as the default
/// out/<scene name>.exr), else in the test's own working directory.
RunResult run_kappa(const std::vector<std::string>& args, const std::filesystem::path& working_dir = {},
                    int timeout_s = 0);

/// run_kappa under a wrapper command, e.g. {"prlimit", "--fsize=4096", "--"}
/// or {"setpriv", "--reuid=65534", ...}: kappa is exec'd by it.
RunResult run_kappa_under(const std::vector<std::string>& wrapper, const std::vector<std::string>& args);

/// `s` quoted for a POSIX shell.
std::string shell_quote(const std::string& s);

/// Whether process `pid` holds a file open in `dir`: a render's outputs,
/// made there unnamed (O_TMPFILE) once its scene is loaded.
bool makes_a_file_in(pid_t pid, const std::filesystem::path& dir);

std::string read_file(const std::filesystem::path& p);
void write_file(const std::filesystem::path& p, const std::string& text);

/// The triangles of one OBJ file (loaded as the renderer loads it).
std::vector<Triangle> load_mesh(const std::filesystem::path& obj);

/// n random triangles in [-1, 1]^3: a centre uniform in the cube, each vertex
/// within +-size of it on every axis (std::mt19937 seeded with `seed`).
std::vector<Triangle> random_soup(std::size_t n, std::uint32_t seed, float size = 0.1f);

/// Appends the 12 triangles of an axis-aligned box with normals facing
/// inwards (`inward`) or outwards, all using material `material`.
void add_box(Scene& scene, const Vec3f& lo, const Vec3f& hi, bool inward, std::uint32_t material);

/// Appends a UV sphere of `rings` x `segments` (closed: poles are shared
/// vertices), normals facing outwards or inwards.
void add_sphere(Scene& scene, const Vec3f& center, float radius, int rings, int segments, bool inward,
                std::uint32_t material);

}  // namespace kappa::test
