// Number parsing must not depend on the locale: under a German locale
// (decimal comma), generated in the test's own folder with localedef, a
// valid scene renders the same image and malformed number rows give the
// same outcome as under C.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "renderer/io/exr_input.h"
#include "test_util.h"

namespace kappa {
namespace {

/// env LOCPATH=... LC_ALL=de_DE.UTF-8, or empty (the test skips) where the
/// locale cannot be generated or does not take effect.
std::vector<std::string> german(const test::TempDir& tmp) {
  const std::string dir = (tmp / "locales").string();
  const std::string gen = "mkdir -p '" + dir + "' && localedef -i de_DE -f UTF-8 '" + dir +
                          "/de_DE.UTF-8' >/dev/null 2>&1";
  if (std::system(gen.c_str()) != 0) return {};
  // The locale is live when printf writes a decimal comma under it.
  const std::string probe = "[ \"$(env LOCPATH='" + dir + "' LC_ALL=de_DE.UTF-8 /usr/bin/printf '%.1f' 1,5)\" = '1,5' ]";
  if (std::system(probe.c_str()) != 0) return {};
  return {"env", "LOCPATH=" + dir, "LC_ALL=de_DE.UTF-8"};
}

TEST(Locale, AGermanLocaleChangesNoNumber) {
  test::TempDir tmp;
  const auto de = german(tmp);
  if (de.empty()) GTEST_SKIP() << "the de_DE.UTF-8 locale cannot be generated here (localedef, i18n sources)";
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  // A valid scene, with fractional numbers on the command line too.
  const auto render = [&](const std::vector<std::string>& wrapper, const std::string& name) {
    const auto r = test::run_kappa_under(
        wrapper, {"render", scene, "--width", "16", "--height", "16", "--spp", "2", "--grid-density", "2.5",
                  "--out", (tmp / (name + ".exr")).string(), "--report", (tmp / (name + ".json")).string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.std_err;
    return nlohmann::json::parse(test::read_file(tmp / (name + ".json")));
  };
  const auto c = render({"env", "LC_ALL=C"}, "c");
  const auto d = render(de, "de");
  EXPECT_EQ(c.at("grid").at("N_c"), d.at("grid").at("N_c"));
  EXPECT_EQ(read_reference(tmp / "c.exr").rgb, read_reference(tmp / "de.exr").rgb);
  // Malformed rows about numbers: the same exit code and message.
  for (const char* file : {"assimp_number_formats_incl_invalid_exponent.obj", "vertex_overflow_1e400.obj",
                           "vertex_huge_1e30.obj"}) {
    SCOPED_TRACE(file);
    const std::vector<std::string> args = {"render", (test::assets_dir() / "malformed" / file).string(), "--width",
                                           "8", "--height", "8", "--spp", "1", "--out",
                                           (tmp / "m.exr").string(), "-q"};
    const auto in_c = test::run_kappa_under({"env", "LC_ALL=C"}, args);
    const auto in_de = test::run_kappa_under(de, args);
    EXPECT_EQ(in_c.exit_code, in_de.exit_code);
    EXPECT_EQ(in_c.std_err, in_de.std_err);
  }
}

}  // namespace
}  // namespace kappa
