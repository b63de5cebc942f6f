#include "renderer/io/calibration_file.h"

#include "core/input_error.h"
#include "core/warning_log.h"

namespace kappa {

std::optional<Calibration> read_calibration_file(const std::filesystem::path& path, bool named) {
  if (!named && calibration_of_another_format(path)) {
    warning_log().add(path.string() +
                      ": a calibration of another format, from another Kappa, is not used: run kappa calibrate again");
    return std::nullopt;
  }
  std::optional<Calibration> c = load_calibration(path);
  if (!c && named) throw InputError(path.string() + ": calibration file not found (make one with kappa calibrate)");
  return c;
}

}  // namespace kappa
