#pragma once

namespace kappa {

/// The git hash Kappa was built from ("-dirty" if the tree had changes).
const char* version_string();

}  // namespace kappa
