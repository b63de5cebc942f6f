#include "renderer/scene/obj/obj_scan.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "renderer/scene/obj/obj_limits.h"

namespace kappa {
namespace {

/// Bytes scanned between progress reports: a few hundred reports for a big mesh.
constexpr std::size_t kProgressBytes = std::size_t(1) << 20;

bool parse_integer(std::string_view tok, long long& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  const auto [p, ec] = std::from_chars(b, e, out);
  return ec == std::errc() && p == e && b != e;
}

std::string excerpt(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string q(s.substr(0, kMax));
  if (s.size() > kMax) q += "...";
  return "'" + q + "'";
}

/// Groups repeated warnings of one kind into a single line.
struct WarningTally {
  std::size_t count = 0;
  std::size_t first_line = 0;
  std::string first_text;

  void add(std::size_t line, std::string_view text) {
    if (count++ == 0) {
      first_line = line;
      first_text = std::string(text);
    }
  }
  void flush(const std::filesystem::path& file, const std::string& what, Warnings& out) const {
    if (count == 0) return;
    std::string msg = std::to_string(count) + " " + what + " (first at line " +
                      std::to_string(first_line) + ": " + excerpt(first_text) + ")";
    out.push_back(located(file, 0, msg));
  }
};

class Scanner {
 public:
  Scanner(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress)
      : m_file(file), m_warnings(warnings), m_progress(progress) {}

  ObjScan run(const std::string& bytes) {
    m_total_vertices = count_statements(bytes, "v");
    m_total_uvs = count_statements(bytes, "vt");
    m_total_normals = count_statements(bytes, "vn");
    std::size_t line_no = 0;
    // A UTF-8 byte-order mark is not part of the first statement.
    std::size_t start = bytes.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
    std::size_t reported = 0;
    while (start < bytes.size()) {
      if (start - reported >= kProgressBytes) {
        advance(m_progress, start - reported);
        reported = start;
      }
      std::size_t end = bytes.find('\n', start);
      if (end == std::string::npos) end = bytes.size();
      std::string_view line(bytes.data() + start, end - start);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      line = without_comment(line);
      ++line_no;
      if (scan_line(line, line_no)) append_with_spaces(m_scan.text, line);
      m_scan.text.push_back('\n');  // keep line numbers aligned, add a final newline
      start = end + 1;
    }
    m_short_faces.flush(m_file, "faces with fewer than 3 vertices skipped", m_warnings);
    m_unknown.flush(m_file, "unknown statements ignored", m_warnings);
    m_non_faces.flush(m_file, "line/point/curve elements ignored (only faces are rendered)", m_warnings);
    return std::move(m_scan);
  }

 private:
  /// Statements of `key` (v, vt, vn) in the whole file.
  static long long count_statements(const std::string& bytes, std::string_view key) {
    long long n = 0;
    std::size_t start = 0;
    while (start < bytes.size()) {
      std::size_t i = start;
      if (start == 0 && bytes.rfind("\xEF\xBB\xBF", 0) == 0) i += 3;
      while (i < bytes.size() && is_blank(bytes[i])) ++i;
      const std::size_t after = i + key.size();
      if (after < bytes.size() && bytes.compare(i, key.size(), key) == 0 && is_blank(bytes[after])) ++n;
      const std::size_t end = bytes.find('\n', start);
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return n;
  }

  /// Returns true to keep the line for tinyobjloader, false to blank it.
  bool scan_line(std::string_view line, std::size_t line_no) {
    const std::vector<std::string_view> tok = split_ws(line);
    if (tok.empty() || tok[0].front() == '#') return true;
    const std::string_view key = tok[0];
    if (key == "v") return scan_vertex(tok, line_no);
    if (key == "vt" || key == "vn") return scan_attribute(tok, line_no);
    if (key == "f") return scan_face(tok, line_no);
    if (key == "mtllib") {
      const auto rest = line.substr(line.find("mtllib") + 6);
      for (auto name : split_ws(rest)) m_scan.mtllibs.emplace_back(name);
      if (split_ws(rest).empty()) warn(line_no, "'mtllib' without a file name ignored");
      return true;
    }
    if (key == "usemtl") {
      // The name is the whole rest of the line: material names may hold spaces.
      std::string_view rest = line.substr(line.find("usemtl") + 6);
      while (!rest.empty() && is_blank(rest.front())) rest.remove_prefix(1);
      while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
      m_scan.material_uses.push_back({line_no, std::string(rest)});
      return true;
    }
    if (key == "g" || key == "o" || key == "s" || key == "vp") return true;
    if (key == "l" || key == "p" || key == "curv" || key == "curv2" || key == "surf") {
      m_non_faces.add(line_no, line);
      return false;
    }
    m_unknown.add(line_no, line);
    return false;
  }

  double coordinate(std::string_view tok, std::size_t line_no, const char* what) {
    double v = 0;
    switch (parse_number(tok, v)) {
      case NumberStatus::invalid:
        fail(m_file, line_no, std::string(what) + " " + excerpt(tok) + " is not a number");
      case NumberStatus::out_of_range:
        fail(m_file, line_no, std::string(what) + " " + excerpt(tok) + " is out of the range of a double");
      case NumberStatus::ok:
        break;
    }
    return v;
  }

  bool scan_vertex(const std::vector<std::string_view>& tok, std::size_t line_no) {
    if (tok.size() < 4)
      fail(m_file, line_no, "vertex needs 3 coordinates, found " + std::to_string(tok.size() - 1));
    Vec3d p;
    for (std::size_t i = 1; i < tok.size(); ++i) {
      const double v = coordinate(tok[i], line_no, "vertex coordinate");
      if (i > 3) continue;  // optional w or vertex colour: syntax checked only
      if (!std::isfinite(v)) fail(m_file, line_no, "vertex coordinate " + excerpt(tok[i]) + " is not finite");
      if (std::abs(v) > kMaxCoordinate) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", kMaxCoordinate);
        fail(m_file, line_no,
             "vertex coordinate " + excerpt(tok[i]) + " exceeds Kappa's limit of " + buf +
                 " (single-precision intersection would overflow); rescale the model");
      }
      (i == 1 ? p.x : i == 2 ? p.y : p.z) = v;
    }
    m_scan.positions.push_back(p);
    return true;
  }

  bool scan_attribute(const std::vector<std::string_view>& tok, std::size_t line_no) {
    if (tok.size() < 2) fail(m_file, line_no, std::string(tok[0]) + " without values");
    for (std::size_t i = 1; i < tok.size(); ++i) coordinate(tok[i], line_no, "value");
    ++(tok[0] == "vt" ? m_defined_uvs : m_defined_normals);
    return true;
  }

  /// A face's vt or vn index: refused when it names nothing (tinyobjloader
  /// would drop it without a word, and the texture coordinates with it).
  void check_attribute_index(long long index, const char* what, long long defined, long long total,
                             std::size_t line_no) {
    if (index == 0) fail(m_file, line_no, std::string("face ") + what + " index 0 is invalid (OBJ indices start at 1)");
    if (index < 0 && (index == std::numeric_limits<long long>::min() || -index > defined))
      fail(m_file, line_no,
           std::string("relative face ") + what + " index " + std::to_string(index) + " points before the first " +
               what + " (" + std::to_string(defined) + " defined so far)");
    if (index > total)
      fail(m_file, line_no,
           std::string("face ") + what + " index " + std::to_string(index) + " is out of range (the file has " +
               std::to_string(total) + " " + what + ")");
  }

  bool scan_face(const std::vector<std::string_view>& tok, std::size_t line_no) {
    if (tok.size() - 1 > kMaxFaceVertices)
      fail(m_file, line_no,
           "a face of " + std::to_string(tok.size() - 1) + " vertices: more than Kappa's limit of " +
               std::to_string(kMaxFaceVertices) + " (triangulating it takes time growing as the square); split it");
    ObjPolygon poly;
    poly.line = line_no;
    for (std::size_t i = 1; i < tok.size(); ++i) {
      const std::string_view ref = tok[i];
      const std::size_t slash = ref.find('/');
      const std::string_view pos = ref.substr(0, slash);
      long long index = 0;
      if (!parse_integer(pos, index))
        fail(m_file, line_no, "face index " + excerpt(pos) + " is not an integer");
      if (slash != std::string_view::npos) {
        // Texture and normal indices must be well-formed and name one.
        std::string_view rest = ref.substr(slash + 1);
        for (std::size_t k = 0; k < 2 && !rest.empty(); ++k) {
          const std::size_t s = rest.find('/');
          const std::string_view part = rest.substr(0, s);
          long long attribute = 0;
          if (!part.empty() && !parse_integer(part, attribute))
            fail(m_file, line_no, "face index " + excerpt(ref) + " is not of the form v, v/vt, v//vn or v/vt/vn");
          if (!part.empty()) {
            if (k == 0) check_attribute_index(attribute, "vt", m_defined_uvs, m_total_uvs, line_no);
            else check_attribute_index(attribute, "vn", m_defined_normals, m_total_normals, line_no);
          }
          if (s == std::string_view::npos) break;
          rest = rest.substr(s + 1);
        }
      }
      const auto defined = static_cast<long long>(m_scan.positions.size());
      if (index == 0) fail(m_file, line_no, "face index 0 is invalid (OBJ indices start at 1)");
      if (index < 0) {
        if (index == std::numeric_limits<long long>::min() || -index > defined)
          fail(m_file, line_no,
               "relative face index " + std::to_string(index) + " points before the first vertex (" +
                   std::to_string(defined) + " defined so far)");
        index = defined + index + 1;
      } else if (index > m_total_vertices) {
        // Positive indices may name vertices defined later in the file, so
        // they are checked against the file's total.
        fail(m_file, line_no,
             "face index " + std::to_string(index) + " is out of range (the file has " +
                 std::to_string(m_total_vertices) + " vertices)");
      }
      poly.vertices.push_back(static_cast<std::size_t>(index - 1));
    }
    if (poly.vertices.size() < 3) {
      m_short_faces.add(line_no, tok.size() == 1 ? std::string_view("f") : tok[0]);
      return false;
    }
    ++m_scan.face_count;
    if (poly.vertices.size() > 3) m_scan.polygons.push_back(std::move(poly));
    return true;
  }

  void warn(std::size_t line, const std::string& msg) { m_warnings.push_back(located(m_file, line, msg)); }

  const std::filesystem::path& m_file;
  Warnings& m_warnings;
  TaskProgress* m_progress;
  ObjScan m_scan;
  long long m_total_vertices = 0;  ///< `v` statements in the whole file
  long long m_total_uvs = 0, m_total_normals = 0;      ///< `vt`, `vn` statements in the whole file
  long long m_defined_uvs = 0, m_defined_normals = 0;  ///< of them, seen so far
  WarningTally m_short_faces, m_unknown, m_non_faces;
};

}  // namespace

NumberStatus parse_number(std::string_view tok, double& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') {
    ++b;
    if (b == e || *b == '+' || *b == '-') return NumberStatus::invalid;
  }
  const auto [p, ec] = std::from_chars(b, e, out, std::chars_format::general);
  if (p != e || b == e) return NumberStatus::invalid;
  if (ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  if (ec != std::errc()) return NumberStatus::invalid;
  return NumberStatus::ok;
}


std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_blank(s[i])) ++i;
    const std::size_t b = i;
    while (i < s.size() && !is_blank(s[i])) ++i;
    if (i > b) out.push_back(s.substr(b, i - b));
  }
  return out;
}

std::string_view without_comment(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i)
    if (line[i] == '#' && (i == 0 || is_blank(line[i - 1]))) {
      line = line.substr(0, i);
      break;
    }
  while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
  return line;
}

void append_with_spaces(std::string& out, std::string_view line) {
  for (char c : line) out.push_back(is_blank(c) ? ' ' : c);
}

ObjScan scan_obj(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress) {
  begin_phase(progress, "reading " + file.filename().string(), 0);
  const std::string bytes = read_input_file(file, "an OBJ file", InputContent::text);
  begin_phase(progress, "checking " + file.filename().string(), bytes.size());
  return Scanner(file, warnings, progress).run(bytes);
}

}  // namespace kappa
