#pragma once
// Private to the ibl module: SIMD vectors for the bake's inner loops. The build keeps GCC's
// default -fmath-errno, under which loops that call std::sqrt are not auto-vectorised (the
// call may set errno); std::experimental::simd (Parallelism TS 2, in libstdc++ since GCC 11,
// also usable with clang) maps sqrt, division and masked updates to vector instructions
// portably. With the baseline x86-64 flags (SSE2) native_simd<float> holds 4 floats.
#include <experimental/simd>

namespace pbrkit::simd {

namespace stdx = std::experimental;
using floatv = stdx::native_simd<float>;
using maskv = floatv::mask_type;
inline constexpr int kLanes = int(floatv::size());

/// Loads kLanes floats from p (any alignment).
inline floatv load(const float* p) {
  return floatv(p, stdx::element_aligned);
}

}  // namespace pbrkit::simd
