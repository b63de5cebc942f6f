// The hostile corpus (tests/data/hostile/cases.json, its README says the
// format): each case made in a fresh folder, kappa run on it under its
// bounds, and its exit code, first (and last) line of standard error, the
// files it must leave untouched, make or not make, and the folder's other
// contents checked.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// One case of the corpus; printed by its name in test listings.
struct Case {
  json spec;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.spec.value("name", "?"); }

std::vector<Case> load_cases() {
  std::ifstream in(source_dir() / "tests" / "data" / "hostile" / "cases.json");
  const json all = json::parse(in);
  std::vector<Case> cases;
  for (const json& c : all) cases.push_back({c});
  return cases;
}

/// A file's content from its description: a string, a flood ({head, repeat
/// with {i} numbered, times, tail}) or a regular polygon ({polygon: n}, its
/// n vertices and one face).
std::string content_of(const json& spec) {
  if (spec.is_string()) return spec.get<std::string>();
  std::string out = spec.value("head", "");
  if (spec.contains("polygon")) {
    const int n = spec["polygon"];
    std::ostringstream s;
    for (int i = 0; i < n; ++i)
      s << "v " << std::cos(6.283185307179586 * i / n) << " " << std::sin(6.283185307179586 * i / n) << " 0\n";
    s << "f";
    for (int i = 1; i <= n; ++i) s << " " << i;
    s << "\n";
    out += s.str();
  }
  const std::string repeat = spec.value("repeat", "");
  for (int i = 0; i < spec.value("times", 0); ++i) {
    std::string piece = repeat;
    for (std::size_t at; (at = piece.find("{i}")) != std::string::npos;) piece.replace(at, 3, std::to_string(i));
    out += piece;
  }
  return out + spec.value("tail", "");
}

/// Every path under `dir`, relative, links not followed.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  std::error_code ec;  // a loop of links is listed, not followed
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    names.insert(it->path().lexically_relative(dir).string());
  }
  return names;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class HostileCorpus : public ::testing::TestWithParam<Case> {};

TEST_P(HostileCorpus, BehavesAsItsCaseSays) {
  const json& c = GetParam().spec;
  TempDir tmp;
  const fs::path dir = tmp / "case";
  if (c.value("base", "") == "cornell") fs::copy(assets_dir() / "cornell-box", dir, fs::copy_options::recursive);
  else fs::create_directory(dir);
  // Each list held in a variable: items() of a temporary would dangle.
  const json dirs = c.value("dirs", json::array()), files = c.value("files", json::object()),
             sparse = c.value("sparse", json::object()), links = c.value("links", json::object()),
             untouched = c.value("untouched", json::array()), absent = c.value("absent", json::array()),
             made = c.value("made", json::array());
  for (const auto& d : dirs) fs::create_directories(dir / d.get<std::string>());
  for (const auto& [name, spec] : files.items()) write_file(dir / name, content_of(spec));
  for (const auto& [name, size] : sparse.items()) fs::resize_file(dir / name, size.get<std::uintmax_t>());
  for (const auto& [name, to] : links.items()) fs::create_symlink(to.get<std::string>(), dir / name);
  std::map<std::string, std::string> before;
  for (const auto& name : untouched) before[name] = read_file(dir / name.get<std::string>());
  const std::set<std::string> made_before = listing(dir);

#ifdef KAPPA_SANITIZED
  // AddressSanitizer reserves terabytes of address space and doubles memory:
  // limits and memory bounds are checked in the plain build only.
  if (c.contains("ulimit_v_mb")) GTEST_SKIP() << "runs under ulimit -v, which the sanitizers' runtime cannot";
  const bool bound_memory = false;
#else
  const bool bound_memory = true;
#endif
  std::string command = "cd " + shell_quote(dir.string()) + " && ";
  if (c.contains("ulimit_v_mb")) command += "ulimit -v " + std::to_string(c["ulimit_v_mb"].get<long>() * 1024) + " && ";
  command += "exec /usr/bin/time -f '%M %e' -o " + shell_quote((tmp / "time").string()) + " timeout " +
             std::to_string(c.value("max_s", 120)) + " " + shell_quote(KAPPA_BINARY);
  for (const auto& a : c["args"]) {
    if (a == "$QUICK") command += " --spp 1 --width 8 --height 8 -q --stats off";
    else command += " " + shell_quote(a.get<std::string>());
  }
  command += " </dev/null >" + shell_quote((tmp / "out").string()) + " 2>" + shell_quote((tmp / "err").string());
  const int status = std::system(("bash -c " + shell_quote(command)).c_str());
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  const std::string err = read_file(tmp / "err");
  const std::vector<std::string> lines = lines_of(err);

  EXPECT_NE(code, 124) << "ran past its " << c.value("max_s", 120) << " s: " << err;
  EXPECT_EQ(code, c["exit"].get<int>()) << err;
  if (c.contains("first_line")) {
    ASSERT_FALSE(lines.empty()) << "no message";
    EXPECT_TRUE(std::regex_search(lines.front(), std::regex(c["first_line"].get<std::string>()))) << lines.front();
  }
  if (c.contains("last_line")) {
    ASSERT_FALSE(lines.empty()) << "no message";
    EXPECT_TRUE(std::regex_search(lines.back(), std::regex(c["last_line"].get<std::string>()))) << lines.back();
  }
  if (c.contains("max_lines")) EXPECT_LE(lines.size(), c["max_lines"].get<std::size_t>()) << err;
  if (c.contains("max_rss_mb") && bound_memory) {
    long rss_kb = 0;
    double seconds = 0;
    std::istringstream(read_file(tmp / "time")) >> rss_kb >> seconds;
    EXPECT_LE(rss_kb, c["max_rss_mb"].get<long>() * 1024) << "peak memory " << rss_kb << " KB";
  }
  for (const auto& [name, bytes] : before) EXPECT_EQ(read_file(dir / name), bytes) << name << " was changed";
  for (const auto& name : absent) EXPECT_FALSE(fs::exists(fs::symlink_status(dir / name.get<std::string>()))) << name;
  std::set<std::string> expected = made_before;
  for (const auto& name : made) {
    EXPECT_TRUE(fs::is_regular_file(dir / name.get<std::string>())) << name << " was not made";
    expected.insert(name.get<std::string>());
  }
  const std::set<std::string> after = listing(dir);
  for (const auto& name : after) EXPECT_TRUE(expected.count(name)) << name << " appeared in the folder";
}

INSTANTIATE_TEST_SUITE_P(Cases, HostileCorpus, ::testing::ValuesIn(load_cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.spec["name"].get<std::string>(); });

}  // namespace
}  // namespace kappa::test
