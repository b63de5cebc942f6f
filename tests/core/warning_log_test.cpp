// The warning log: each kind printed for its first 5 occurrences, then
// counted and summed up at the end, whatever the file, line, names and
// numbers of each.
#include "core/warning_log.h"

#include <gtest/gtest.h>

namespace kappa {
namespace {

TEST(WarningKind, IsTheTextWithoutLocationNamesAndNumbers) {
  EXPECT_EQ(warning_kind("a.obj:12: material 'red' is not defined; using the default grey"),
            "material '...' is not defined; using the default grey");
  EXPECT_EQ(warning_kind("dir/b.obj:4000: material 'blue green' is not defined; using the default grey"),
            warning_kind("a.obj:12: material 'red' is not defined; using the default grey"));
  EXPECT_EQ(warning_kind("scene.json: mesh 'x.obj' is listed twice: its triangles, and any emitters, count twice"),
            "mesh '...' is listed twice: its triangles, and any emitters, count twice");
  EXPECT_EQ(warning_kind("12,345 samples had non-finite radiance"), "N samples had non-finite radiance");
  // A leading phrase with spaces is not a location.
  EXPECT_EQ(warning_kind("--length applies to --rays segments only; ignored"),
            "--length applies to --rays segments only; ignored");
  EXPECT_NE(warning_kind("a.obj:1: concave polygon with 6 vertices"), warning_kind("a.obj:1: 6 zero-area triangles dropped"));
}

TEST(WarningLog, PrintsTheFirstFiveOfAKindThenSumsUpTheRest) {
  WarningLog log;
  testing::internal::CaptureStderr();
  for (int i = 0; i < 300; ++i) log.add("m.obj:" + std::to_string(i + 4) + ": material 'm" + std::to_string(i) + "' is not defined");
  log.add("m.obj: 3 zero-area triangles dropped");
  log.finish();
  log.add("m.obj:900: material 'late' is not defined");
  log.finish();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err,
            "kappa: warning: m.obj:4: material 'm0' is not defined\n"
            "kappa: warning: m.obj:5: material 'm1' is not defined\n"
            "kappa: warning: m.obj:6: material 'm2' is not defined\n"
            "kappa: warning: m.obj:7: material 'm3' is not defined\n"
            "kappa: warning: m.obj:8: material 'm4' is not defined\n"
            "kappa: warning: m.obj: 3 zero-area triangles dropped\n"
            "kappa: warning: ... and 295 more like it: material '...' is not defined\n"
            "kappa: warning: ... and 1 more like it: material '...' is not defined\n");
  const std::vector<WarningKind> kinds = log.kinds();
  ASSERT_EQ(kinds.size(), 2u);
  EXPECT_EQ(kinds[0].count, 301u);
  EXPECT_EQ(kinds[0].first, "m.obj:4: material 'm0' is not defined");
  EXPECT_EQ(kinds[1].count, 1u);
}

}  // namespace
}  // namespace kappa
