// Which sampler a frame draws its numbers from (samplers.h), chosen once per
// frame; apart from the samplers so that a frame's settings need not see them.
#pragma once

#include <string>

namespace kappa {

enum class SamplerKind { independent, stratified, sobol };

/// "independent", "stratified", "sobol".
const char* sampler_name(SamplerKind kind);
/// The kind of a --sampler name; throws InputError for another.
SamplerKind parse_sampler(const std::string& name);
/// Whether the sampler needs the samples per pixel in advance (a budget,
/// which decides them as it goes, cannot use it).
inline bool needs_total(SamplerKind kind) { return kind == SamplerKind::stratified; }

}  // namespace kappa
