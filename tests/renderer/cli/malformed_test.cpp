// The bad-input policy is documented once, in docs/bad-input.md's "## Bad input"
// table, and this file checks the binary against it: every input file in
// assets/malformed/ has a row, and every row's outcome (refuse / warn / load)
// is what `kappa render` actually does with that file. A behaviour change
// therefore needs a docs/bad-input.md change, and vice versa.
#include <gtest/gtest.h>

#include "image_files.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <regex>
#include <set>

#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

fs::path malformed_dir() { return assets_dir() / "malformed"; }

// ---------------------------------------------------------------------------
// The policy table

enum class Outcome { refuse, warn, load, unknown };

struct PolicyRow {
  std::string file;      ///< name inside assets/malformed
  std::size_t columns = 0;
  std::string outcome_cell;
  Outcome outcome = Outcome::unknown;
  std::optional<int> line;  ///< `refuse (line N)`: the error must say FILE:N:
  std::string message;   ///< the whole message cell
  std::string fragment;  ///< its first code span: part of what Kappa prints
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

/// "| a | b |" -> {"a", "b"}. The table has no escaped pipes, by convention.
std::vector<std::string> split_cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string body = trim(row);
  if (body.front() == '|') body.erase(0, 1);
  if (!body.empty() && body.back() == '|') body.pop_back();
  std::size_t start = 0;
  for (std::size_t bar; (bar = body.find('|', start)) != std::string::npos; start = bar + 1)
    cells.push_back(trim(body.substr(start, bar - start)));
  cells.push_back(trim(body.substr(start)));
  return cells;
}

std::string strip_backticks(const std::string& s) {
  if (s.size() >= 2 && s.front() == '`' && s.back() == '`') return s.substr(1, s.size() - 2);
  return s;
}

std::string first_code_span(const std::string& s) {
  const auto open = s.find('`');
  if (open == std::string::npos) return "";
  const auto close = s.find('`', open + 1);
  if (close == std::string::npos) return "";
  return s.substr(open + 1, close - open - 1);
}

void parse_outcome(PolicyRow& row) {
  static const std::regex pattern(R"(^(refuse|warn|load)(?: \(line ([0-9]+)\))?$)");
  std::smatch m;
  if (!std::regex_match(row.outcome_cell, m, pattern)) return;
  row.outcome = m[1] == "refuse" ? Outcome::refuse : m[1] == "warn" ? Outcome::warn : Outcome::load;
  // A line number only makes sense for a refusal; elsewhere it stays unknown.
  if (m[2].matched) {
    if (row.outcome != Outcome::refuse) row.outcome = Outcome::unknown;
    row.line = std::stoi(m[2]);
  }
}

/// The rows of the first table under "## Bad input" in docs/bad-input.md. Empty if
/// the section or its table is missing: the coverage test then fails.
std::vector<PolicyRow> read_policy_table() {
  std::ifstream in(source_dir() / "docs" / "bad-input.md");
  std::vector<PolicyRow> rows;
  bool in_section = false, in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) {
      if (in_section) break;
      in_section = trim(line) == "## Bad input";
      continue;
    }
    if (!in_section) continue;
    const bool table_line = trim(line).rfind('|', 0) == 0;
    if (!table_line) {
      if (in_table) break;  // the table ended
      continue;
    }
    const std::vector<std::string> cells = split_cells(line);
    if (!in_table) {  // header row
      in_table = true;
      continue;
    }
    if (cells[0].find_first_not_of("-: ") == std::string::npos) continue;  // |---|
    PolicyRow row;
    row.file = strip_backticks(cells[0]);
    row.columns = cells.size();
    if (cells.size() == 4) {
      row.outcome_cell = cells[2];
      row.message = cells[3];
      row.fragment = first_code_span(row.message);
      parse_outcome(row);
    }
    rows.push_back(row);
  }
  return rows;
}

const std::vector<PolicyRow>& policy_rows() {
  static const std::vector<PolicyRow> rows = read_policy_table();
  return rows;
}

/// One row per file, so a duplicated row does not break test registration
/// (the coverage test reports duplicates).
std::vector<PolicyRow> unique_policy_rows() {
  std::vector<PolicyRow> unique;
  std::set<std::string> seen;
  for (const PolicyRow& row : policy_rows())
    if (seen.insert(row.file).second) unique.push_back(row);
  return unique;
}

/// Inputs are OBJ and scene files; MTL files are only ever read through an OBJ.
std::set<std::string> malformed_inputs() {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(malformed_dir())) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".obj" || ext == ".json") names.insert(entry.path().filename().string());
  }
  return names;
}

TEST(MalformedPolicyTable, HasOneRowPerInputFile) {
  const std::set<std::string> inputs = malformed_inputs();
  ASSERT_FALSE(inputs.empty()) << malformed_dir();
  ASSERT_FALSE(policy_rows().empty()) << "no table under '## Bad input' in docs/bad-input.md";
  std::map<std::string, int> count;
  for (const PolicyRow& row : policy_rows()) ++count[row.file];
  for (const auto& [file, n] : count) {
    EXPECT_EQ(n, 1) << file << " has " << n << " rows";
    EXPECT_TRUE(inputs.count(file)) << "the table names " << file << ", which is not an input in " << malformed_dir();
  }
  for (const std::string& file : inputs) EXPECT_TRUE(count.count(file)) << file << " has no row in the policy table";
}

TEST(MalformedPolicyTable, RowsAreWellFormed) {
  for (const PolicyRow& row : policy_rows()) {
    SCOPED_TRACE(row.file);
    EXPECT_EQ(row.columns, 4u) << "| file | what is wrong | outcome | message |";
    EXPECT_NE(row.outcome, Outcome::unknown)
        << "outcome '" << row.outcome_cell << "' is not refuse, refuse (line N), warn or load";
    // Refusals and warnings quote Kappa, so a changed message shows up here.
    if (row.outcome == Outcome::refuse || row.outcome == Outcome::warn) {
      EXPECT_FALSE(row.fragment.empty()) << "the message column needs a `quoted` part of Kappa's message";
    }
  }
}

// ---------------------------------------------------------------------------
// Reading the output

/// The values of one channel of an EXR, or an empty vector (and a test
/// failure) if the file or channel cannot be read.
std::vector<float> read_channel(const fs::path& exr, const std::string& channel) {
  const test::ExrFile image = test::read_exr_file(exr);
  if (image.channel(channel) < 0) {
    ADD_FAILURE() << exr << " has no channel " << channel;
    return {};
  }
  return image.values(channel);
}

void expect_finite_rgb(const fs::path& exr) {
  for (const char* channel : {"R", "G", "B"}) {
    const std::vector<float> v = read_channel(exr, channel);
    EXPECT_FALSE(v.empty()) << channel;
    const auto bad = std::find_if(v.begin(), v.end(), [](float x) { return !std::isfinite(x); });
    if (bad != v.end()) ADD_FAILURE() << channel << " of " << exr << " is " << *bad << " at pixel " << (bad - v.begin());
  }
}

std::vector<std::string> folder_entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// ---------------------------------------------------------------------------
// Each row against the binary

RunResult render_tiny(const fs::path& scene, const fs::path& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", scene.string(), "--spp", "1", "--width", "16", "--height", "16",
                                   "--out", out.string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_kappa(args);
}

/// The file a refusal must name: the row's own file, unless the quoted
/// message starts with another file's name (a scene refused for its mesh).
std::string named_file(const PolicyRow& row) {
  static const std::regex leading_name(R"(^([^\s:/]+\.(obj|json)):)");
  std::smatch m;
  if (std::regex_search(row.fragment, m, leading_name)) return m[1];
  return row.file;
}

void expect_refused(const PolicyRow& row, const RunResult& r, const fs::path& tmp) {
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  const std::vector<std::string> lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << "a refusal is exactly one line on stderr:\n" << r.std_err;
  const std::string& line = lines[0];
  EXPECT_TRUE(starts_with(line, "kappa: error: ")) << line;
  const std::string name = named_file(row);
  EXPECT_TRUE(contains(line, name)) << "does not name " << name << ": " << line;
  if (row.line) {
    const std::string located = name + ":" + std::to_string(*row.line) + ":";
    EXPECT_TRUE(contains(line, located)) << "does not say " << located << ": " << line;
  }
  EXPECT_TRUE(contains(line, row.fragment)) << "does not say '" << row.fragment << "': " << line;
  // Neither the EXR nor AtomicOutput's temporary may be left behind.
  EXPECT_TRUE(folder_entries(tmp).empty()) << "left behind: " << ::testing::PrintToString(folder_entries(tmp));
}

void expect_rendered(const RunResult& r, const fs::path& tmp, const fs::path& out) {
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  ASSERT_TRUE(fs::is_regular_file(out)) << r.std_err;
  EXPECT_EQ(folder_entries(tmp), std::vector<std::string>{out.filename().string()}) << "stray temporary?";
  expect_finite_rgb(out);
}

void expect_warned(const PolicyRow& row, const RunResult& r, const fs::path& tmp, const fs::path& out) {
  expect_rendered(r, tmp, out);
  const std::vector<std::string> lines = r.err_lines();
  EXPECT_FALSE(lines.empty()) << "expected at least one warning";
  bool quoted = false;
  for (const std::string& line : lines) {
    // With --quiet there is no summary line: everything on stderr is a warning.
    EXPECT_TRUE(starts_with(line, "kappa: warning: ")) << line;
    quoted |= contains(line, row.fragment);
  }
  EXPECT_TRUE(quoted) << "no warning says '" << row.fragment << "':\n" << r.std_err;
}

// Names the row in gtest's listings instead of dumping the struct's bytes.
void PrintTo(const PolicyRow& row, std::ostream* os) { *os << row.file << ": " << row.outcome_cell; }

class MalformedPolicy : public ::testing::TestWithParam<PolicyRow> {};

TEST_P(MalformedPolicy, BinaryFollowsTheTable) {
  const PolicyRow& row = GetParam();
  SCOPED_TRACE(row.file + ": " + row.outcome_cell);
  const fs::path input = malformed_dir() / row.file;
  ASSERT_TRUE(fs::is_regular_file(input)) << input;
  TempDir tmp;
  const fs::path out = tmp / "x.exr";
  const RunResult r = render_tiny(input, out);
  switch (row.outcome) {
    case Outcome::refuse:
      expect_refused(row, r, tmp.path());
      break;
    case Outcome::warn:
      expect_warned(row, r, tmp.path(), out);
      break;
    case Outcome::load:
      expect_rendered(r, tmp.path(), out);
      EXPECT_EQ(r.std_err, "") << "a clean load prints nothing with --quiet";
      break;
    case Outcome::unknown:
      FAIL() << "unparseable outcome '" << row.outcome_cell << "'";
  }
}

std::string row_test_name(const ::testing::TestParamInfo<PolicyRow>& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name.empty() ? "row" + std::to_string(info.index) : name;
}

INSTANTIATE_TEST_SUITE_P(Readme, MalformedPolicy, ::testing::ValuesIn(unique_policy_rows()), row_test_name);

// ---------------------------------------------------------------------------
// Default grey: a material that cannot be found is not a refusal, and the
// surface really gets the documented grey (Kd 0.5), not black or garbage.

/// The largest albedo.R of a tiny render with the albedo AOV: Kd of the
/// material hit by pixels fully inside the triangle.
float max_albedo(const fs::path& input, RunResult& r) {
  TempDir tmp;
  const fs::path out = tmp / "x.exr";
  r = render_tiny(input, out, {"--aov", "albedo"});
  if (r.exit_code != 0 || !fs::is_regular_file(out)) return -1.0f;
  const std::vector<float> albedo = read_channel(out, "albedo.R");
  return albedo.empty() ? -1.0f : *std::max_element(albedo.begin(), albedo.end());
}

bool any_line_contains(const RunResult& r, const std::string& text) {
  const auto lines = r.err_lines();
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return contains(l, text); });
}

TEST(DefaultGrey, MissingMaterialLibrary) {
  RunResult r;
  EXPECT_FLOAT_EQ(max_albedo(malformed_dir() / "missing_mtl_file.obj", r), 0.5f) << r.std_err;
  EXPECT_TRUE(any_line_contains(
      r, "kappa: warning: " + (malformed_dir() / "missing_mtl_file.obj").string() +
             ": material library 'does_not_exist.mtl' not found; its materials use the default grey"))
      << r.std_err;
}

TEST(DefaultGrey, UnknownMaterial) {
  RunResult r;
  EXPECT_FLOAT_EQ(max_albedo(malformed_dir() / "unknown_material.obj", r), 0.5f) << r.std_err;
  EXPECT_TRUE(any_line_contains(r, "unknown_material.obj:3: material 'no_such_material' is not defined; using the default grey"))
      << r.std_err;
}

TEST(DefaultGrey, ControlUsesItsOwnMaterial) {
  // ok_triangle.obj has the same triangle with Kd 0.8 from ok.mtl: the grey
  // above comes from the fallback, not from the camera or the AOV.
  RunResult r;
  EXPECT_NEAR(max_albedo(malformed_dir() / "ok_triangle.obj", r), 0.8f, 1e-6f) << r.std_err;
  EXPECT_EQ(r.std_err, "");
}

}  // namespace
}  // namespace kappa::test
