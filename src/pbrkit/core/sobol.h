#pragma once
// The two parts of the Owen-scrambled Sobol sampler (core/sampling.h), private: the
// sampler's own sampling.cpp and its tests use them (the first dimensions are known in
// closed form, and the scramble's nesting is a property of its own).
#include <cstdint>

namespace pbrkit {

/// Plain (unscrambled) Sobol point `index` in dimension `dim` (0..3), as a 32-bit integer
/// fraction.
std::uint32_t sobol_u32(std::uint32_t index, std::uint32_t dim);
/// Burley 2020's hash-based nested uniform (Owen) scramble of a 32-bit fraction.
std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed);

}  // namespace pbrkit
