// The layout docs/how-it-is-built.md's "How it is built" describes, read off the sources:
// renderer/ holds rooms with only main.cpp and a few shared headers at its
// top, no component includes itself through others, no two rooms depend on
// each other, no command includes another, and the libraries below the
// renderer never include a higher floor (core <- accel <- stats <- renderer).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "test_util.h"

namespace kappa {
namespace {

namespace fs = std::filesystem;

/// A component is a header and its source file together ("renderer/scene/obj/obj_scan").
using Graph = std::map<std::string, std::set<std::string>>;

/// grid_traverse.h is the body of grid.h's member templates (the walk, for
/// any recorder): part of the grid's component, not a layer above or below it;
/// grid2_traverse.h likewise of grid2's.
std::string component_of(const std::string& path) {
  const std::string c = fs::path(path).replace_extension().string();
  if (c == "accel/grid_traverse") return "accel/grid";
  return c == "accel/grid2_traverse" ? "accel/grid2" : c;
}

/// Every #include "..." of every .h and .cpp under the given top folders, as
/// edges between components (paths relative to the source tree).
Graph include_graph(const std::vector<std::string>& tops) {
  static const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\")");
  Graph g;
  for (const auto& top : tops) {
    for (const auto& entry : fs::recursive_directory_iterator(test::source_dir() / top)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string file = fs::relative(entry.path(), test::source_dir()).string();
      const std::string from = component_of(file);
      g[from];
      std::ifstream in(entry.path());
      std::string line;
      std::smatch m;
      while (std::getline(in, line)) {
        if (!std::regex_search(line, m, include)) continue;
        std::string target = m[1];
        // Includes are from the source tree's root, or (in accel/ and stats/)
        // beside the including file.
        if (!fs::exists(test::source_dir() / target))
          target = (fs::path(file).parent_path() / target).lexically_normal().string();
        if (!fs::exists(test::source_dir() / target)) continue;  // a system or generated header
        const std::string to = component_of(target);
        if (to != from) g[from].insert(to);
      }
    }
  }
  return g;
}

/// One cycle of `g` as "a -> b -> a", or empty if it has none.
std::string find_cycle(const Graph& g) {
  std::map<std::string, int> state;  // 0 unvisited, 1 on the stack, 2 done
  std::vector<std::string> stack;
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& v) {
    state[v] = 1;
    stack.push_back(v);
    const auto it = g.find(v);
    if (it != g.end()) {
      for (const auto& w : it->second) {
        if (state[w] == 1) {
          for (auto s = std::find(stack.begin(), stack.end(), w); s != stack.end(); ++s) cycle += *s + " -> ";
          cycle += w;
          return true;
        }
        if (state[w] == 0 && visit(w)) return true;
      }
    }
    stack.pop_back();
    state[v] = 2;
    return false;
  };
  for (const auto& [v, _] : g)
    if (state[v] == 0 && visit(v)) return cycle;
  return {};
}

/// "stats/cast" -> "stats": the top folder.
std::string library_of(const std::string& component) { return fs::path(component).begin()->string(); }

/// "renderer/scene/obj/obj_scan" -> "scene"; a file at renderer/'s top (main, a
/// shared header) is a room of its own: "main", "version".
std::string room_of(const std::string& component) {
  const fs::path p(component);
  auto it = std::next(p.begin());
  return it == p.end() ? "" : it->string();
}

TEST(Layout, RendererTopHoldsOnlyMainAndSharedHeaders) {
  const std::set<std::string> allowed = {"main.cpp", "version.h", "CMakeLists.txt"};
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "renderer")) {
    if (entry.is_directory()) continue;
    EXPECT_TRUE(allowed.count(entry.path().filename().string())) << entry.path() << " belongs in a room of renderer/";
  }
}

TEST(Layout, NoComponentIncludesItselfThroughOthers) {
  const Graph g = include_graph({"core", "accel", "stats", "renderer"});
  EXPECT_GT(g.size(), 40u);  // the walk found the sources
  EXPECT_EQ(find_cycle(g), "");
}

TEST(Layout, RoomsOfTheRendererFormNoCycle) {
  Graph rooms;
  for (const auto& [from, targets] : include_graph({"renderer"})) {
    for (const auto& to : targets) {
      const std::string a = room_of(from), b = room_of(to);
      if (library_of(to) == "renderer" && a != b) rooms[a].insert(b);
    }
  }
  EXPECT_TRUE(rooms.count("commands"));  // the graph has the rooms' edges
  EXPECT_EQ(find_cycle(rooms), "");
}

TEST(Layout, NoCommandIncludesAnother) {
  for (const auto& [from, targets] : include_graph({"renderer"})) {
    if (room_of(from) != "commands") continue;
    for (const auto& to : targets) EXPECT_NE(room_of(to), "commands") << from << " includes " << to;
  }
}

/// The floors, lowest first (cmake/floors.cmake): a floor includes its own
/// and lower ones only. The build refuses an upward include too
/// (Build.Floors.*); this also catches one written as a relative path.
int floor_of(const std::string& library) {
  static const std::map<std::string, int> floors = {{"core", 0}, {"accel", 1}, {"stats", 2}, {"renderer", 3}};
  const auto it = floors.find(library);
  return it == floors.end() ? 99 : it->second;
}

TEST(Layout, NoFloorIncludesAHigherOne) {
  int edges = 0;
  for (const auto& [from, targets] : include_graph({"core", "accel", "stats", "renderer"}))
    for (const auto& to : targets) {
      EXPECT_LE(floor_of(library_of(to)), floor_of(library_of(from))) << from << " includes " << to;
      ++edges;
    }
  EXPECT_GT(edges, 100);
  // core/ is the ground floor: it includes only itself.
  for (const auto& [from, targets] : include_graph({"core"}))
    for (const auto& to : targets) EXPECT_EQ(library_of(to), "core") << from << " includes " << to;
}

/// docs/how-it-is-built.md's "How it is built" section.
std::string how_it_is_built() {
  std::ifstream in(test::source_dir() / "docs" / "how-it-is-built.md");
  const std::string readme((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto begin = readme.find("## How it is built");
  if (begin == std::string::npos) return {};
  return readme.substr(begin, readme.find("\n## ", begin + 1) - begin);
}

/// Every source file name under the folders docs/how-it-is-built.md describes.
std::set<std::string> source_file_names() {
  std::set<std::string> names;
  for (const char* top : {"core", "accel", "stats", "renderer", "tests", "tools"})
    for (const auto& entry : fs::recursive_directory_iterator(test::source_dir() / top))
      if (entry.is_regular_file()) names.insert(entry.path().filename().string());
  return names;
}

TEST(Layout, HowItIsBuiltNamesOnlyFilesAndFoldersThatExist) {
  const std::string section = how_it_is_built();
  ASSERT_FALSE(section.empty()) << "docs/how-it-is-built.md has no \"How it is built\" section";
  const std::set<std::string> names = source_file_names();
  static const std::regex code("`([^`]+)`");
  static const std::regex source_name(R"(^[\w*]+\.(h|cpp|sh)$)");
  int checked = 0;
  for (auto it = std::sregex_iterator(section.begin(), section.end(), code); it != std::sregex_iterator(); ++it) {
    const std::string token = (*it)[1];
    if (token.find('<') != std::string::npos || token.find(' ') != std::string::npos) continue;
    if (token.rfind("../", 0) == 0) continue;  // beside the checkout (../shared), absent from a user's clone
    if (token.find('/') != std::string::npos) {  // a path from the source tree's root
      EXPECT_TRUE(fs::exists(test::source_dir() / token)) << token;
      ++checked;
    } else if (std::regex_match(token, source_name)) {  // a file named by itself, perhaps with a *
      const std::regex pattern(std::regex_replace(std::regex_replace(token, std::regex(R"(\.)"), R"(\.)"),
                                                  std::regex(R"(\*)"), ".*"));
      EXPECT_TRUE(std::any_of(names.begin(), names.end(), [&](const std::string& n) { return std::regex_match(n, pattern); }))
          << token;
      ++checked;
    }
  }
  EXPECT_GT(checked, 40);
}

TEST(Layout, HowItIsBuiltHasARowForEveryRoom) {
  const std::string section = how_it_is_built();
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "renderer")) {
    if (!entry.is_directory()) continue;
    const std::string row = "| `renderer/" + entry.path().filename().string() + "/` |";
    EXPECT_NE(section.find(row), std::string::npos) << row;
  }
  for (const char* top : {"core", "accel", "stats", "tests", "tools", "assets"})
    EXPECT_NE(section.find(std::string("| `") + top + "/` |"), std::string::npos) << top;
}

}  // namespace
}  // namespace kappa
