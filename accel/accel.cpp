#include "accel.h"

#include <nlohmann/json.hpp>

namespace kappa {

nlohmann::ordered_json Accelerator::report_section() const { return nullptr; }

}  // namespace kappa
