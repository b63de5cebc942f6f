#include "test_util.h"

#include "renderer/scene/obj/obj_loader.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <random>

namespace kappa::test {

double test_scale() {
  static const double scale = [] {
    const char* text = std::getenv("KAPPA_TEST_SCALE");
    if (text == nullptr || *text == '\0') return 1.0;
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (*end != '\0' || !(v > 0 && v <= 1)) {
      std::fprintf(stderr, "KAPPA_TEST_SCALE=%s: expected a number in (0, 1]\n", text);
      std::abort();
    }
    return v;
  }();
  return scale;
}

int scaled(int n, int at_least) {
  return std::max(at_least, int(std::lround(double(n) * test_scale())));
}

double noise_widening(int n, int at_least) { return std::sqrt(double(n) / double(scaled(n, at_least))); }

bool bitwise_equal(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TempDir::TempDir() {
  static std::mt19937_64 rng(std::random_device{}());
  m_path = std::filesystem::temp_directory_path() /
           ("kappa-test-" + std::to_string(::getpid()) + "-" + std::to_string(rng()));
  std::filesystem::create_directories(m_path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(m_path, ec);
}

std::vector<std::string> RunResult::err_lines() const {
  std::vector<std::string> lines;
  std::istringstream in(std_err);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  return q + "'";
}

bool makes_a_file_in(pid_t pid, const std::filesystem::path& dir) {
  std::error_code ec;
  const std::string folder = std::filesystem::canonical(dir, ec).string() + "/";
  for (const auto& fd : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec)) {
    const auto to = std::filesystem::read_symlink(fd.path(), ec);
    if (!ec && to.string().rfind(folder, 0) == 0) return true;
  }
  return false;
}

namespace {

RunResult run_command(const std::vector<std::string>& wrapper, const std::vector<std::string>& args,
                      const std::filesystem::path& working_dir, int timeout_s) {
  TempDir tmp;
  // With a timeout, a run that hangs ends with exit code 124 (coreutils' timeout).
  std::string cmd = timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " " : std::string();
  for (const auto& w : wrapper) cmd += shell_quote(w) + " ";
  cmd += shell_quote(KAPPA_BINARY);
  for (const auto& a : args) cmd += " " + shell_quote(a);
  // In a subshell, so that a failing cd reports into the captured stderr too.
  if (!working_dir.empty()) cmd = "(cd " + shell_quote(working_dir.string()) + " && exec " + cmd + ")";
  cmd += " </dev/null 2>" + shell_quote((tmp / "stderr").string()) + " >" + shell_quote((tmp / "stdout").string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.std_err = read_file(tmp / "stderr");
  r.std_out = read_file(tmp / "stdout");
  return r;
}

}  // namespace

RunResult run_kappa(const std::vector<std::string>& args, const std::filesystem::path& working_dir, int timeout_s) {
  return run_command({}, args, working_dir, timeout_s);
}

RunResult run_kappa_under(const std::vector<std::string>& wrapper, const std::vector<std::string>& args) {
  return run_command(wrapper, args, {}, 0);
}

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

std::vector<Triangle> load_mesh(const std::filesystem::path& obj) {
  Scene s;
  Warnings w;
  load_obj(obj, s, w);
  return s.triangles;
}

std::vector<Triangle> random_soup(std::size_t n, std::uint32_t seed, float size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-1.0f, 1.0f), edge(-size, size);
  std::vector<Triangle> tris;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3f c{pos(rng), pos(rng), pos(rng)};
    tris.push_back({c + Vec3f{edge(rng), edge(rng), edge(rng)}, c + Vec3f{edge(rng), edge(rng), edge(rng)},
                    c + Vec3f{edge(rng), edge(rng), edge(rng)}});
  }
  return tris;
}

namespace {
void add_quad(Scene& scene, Vec3f a, Vec3f b, Vec3f c, Vec3f d, bool flip, std::uint32_t material) {
  if (flip) std::swap(b, d);
  scene.triangles.push_back({a, b, c});
  scene.triangles.push_back({a, c, d});
  scene.material_of.push_back(material);
  scene.material_of.push_back(material);
}
}  // namespace

void add_box(Scene& scene, const Vec3f& lo, const Vec3f& hi, bool inward, std::uint32_t material) {
  const Vec3f p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                      {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  // Counter-clockwise seen from outside: outward normals.
  add_quad(scene, p[0], p[3], p[2], p[1], inward, material);  // -z
  add_quad(scene, p[4], p[5], p[6], p[7], inward, material);  // +z
  add_quad(scene, p[0], p[4], p[7], p[3], inward, material);  // -x
  add_quad(scene, p[1], p[2], p[6], p[5], inward, material);  // +x
  add_quad(scene, p[0], p[1], p[5], p[4], inward, material);  // -y
  add_quad(scene, p[3], p[7], p[6], p[2], inward, material);  // +y
}

void add_sphere(Scene& scene, const Vec3f& center, float radius, int rings, int segments, bool inward,
                std::uint32_t material) {
  auto vertex = [&](int ring, int seg) {
    if (ring == 0) return center + Vec3f{0, radius, 0};
    if (ring == rings) return center + Vec3f{0, -radius, 0};
    const double theta = std::numbers::pi * ring / rings;
    const double phi = 2 * std::numbers::pi * (seg % segments) / segments;
    return center + Vec3f{float(radius * std::sin(theta) * std::cos(phi)), float(radius * std::cos(theta)),
                          float(radius * std::sin(theta) * std::sin(phi))};
  };
  auto add = [&](Vec3f a, Vec3f b, Vec3f c) {
    if (inward) std::swap(b, c);
    scene.triangles.push_back({a, b, c});
    scene.material_of.push_back(material);
  };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const Vec3f a = vertex(r, s), b = vertex(r, s + 1), c = vertex(r + 1, s), d = vertex(r + 1, s + 1);
      // Outward winding: seen from outside, counter-clockwise.
      if (r != 0) add(a, b, d);
      if (r != rings - 1) add(a, d, c);
    }
  }
}

}  // namespace kappa::test
