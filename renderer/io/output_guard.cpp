#include "renderer/io/output_guard.h"

#include "core/error.h"

namespace kappa {
namespace {

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) return std::filesystem::equivalent(a, b, ec);
  const auto ca = std::filesystem::weakly_canonical(a, ec);
  const auto cb = std::filesystem::weakly_canonical(b, ec);
  return !ca.empty() && ca == cb;
}

}  // namespace

void refuse_outputs_over_inputs(const std::vector<std::filesystem::path>& outputs,
                                const std::vector<std::filesystem::path>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].empty()) continue;
    for (const auto& input : inputs)
      if (!input.empty() && same_file(outputs[i], input))
        fail(outputs[i], 0, "is the input file '" + input.string() + "': refusing to overwrite an input");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].empty() && same_file(outputs[i], outputs[j]))
        fail(outputs[i], 0, "is also another output of this run ('" + outputs[j].string() + "'): give each its own file");
  }
}

}  // namespace kappa
