#pragma once
// The lane count of glint's batched geometry. The SIMD switches (GLINT_AVX2, GLINT_AVX512,
// GLINT_NO_SIMD) are glint/instruction_set.hpp's; the numbers its kernels compute in, at every
// width, are math/wide.hpp's.

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The lanes of glint's batched geometry, whatever the instruction set: the rays of a RayBatch,
/// the spheres that a linear set's scan and a BVH leaf group test at once (Float<kBatchWidth>,
/// one AVX2 register), and the eight-lane width of math/lanes.hpp. Every other lane count of
/// the geometry derives from it.
inline constexpr int kBatchWidth = 8;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
