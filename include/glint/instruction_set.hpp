#pragma once
// The instruction set glint's code is compiled for: the switches of its SIMD kernels, and the
// namespace that keeps the code of each instruction set apart.
//
// glint is header-only, and its data layouts and kernels follow the compiler's target: with
// AVX2 a SphereSet keeps its spheres in columns of eight floats, with AVX-512 a sampler's
// 64-bit words travel in 512-bit pieces. Two translation units compiled for different
// instruction sets would each define glint's classes and inline functions their own way under
// the same names, and the linker would keep one of each, silently. So every declaration of
// glint is in an inline namespace named for the instruction set (glint::isa_avx512::Scene),
// which code names as glint::Scene all the same: translation units built for different
// instruction sets link into one program without sharing a definition, and one built for
// another instruction set than a compiled library's fails to link instead of misbehaving.
// glint-render holds its renderer once per instruction set this way and runs the best one the
// CPU has (apps/glint_render.cpp). Outside that namespace are only the types that pass between
// them, whose layouts never depend on it: the exceptions (error.hpp) and Film
// (image/film.hpp).
//
// The kernels test the macros below, never the compiler's own (__AVX2__, ...), so that defining
// GLINT_NO_SIMD turns every one of them back to its scalar reference:
//
//   GLINT_AVX2    8-wide AVX2 + FMA kernels (SphereSet, WallSet, the BVH's nodes, ...)
//   GLINT_AVX512  16-wide AVX-512 forms of the batched ray queries (x86-64-v4: F, VL, BW, DQ)
//
// Each is defined when the compiler targets that instruction set (e.g. -march=native) and
// GLINT_NO_SIMD is not defined. The shading's lanes (math/wide.hpp) follow the compiler's
// target directly: 16 with AVX-512 (see render/wavefront/wavefront_execution.hpp).

#include <string_view>

#if !defined(GLINT_NO_SIMD)
#if defined(__AVX2__) && defined(__FMA__)
#define GLINT_AVX2 1
#endif
#if defined(GLINT_AVX2) && defined(__AVX512F__) && defined(__AVX512VL__) && \
    defined(__AVX512BW__) && defined(__AVX512DQ__)
#define GLINT_AVX512 1
#endif
#endif

// GLINT_ISA_NAMESPACE: the widest instruction set the code may use, among those that change
// what glint compiles, and whether glint's kernels are on.
#if defined(__AVX512F__)
#define GLINT_ISA_LEVEL avx512
#elif defined(__AVX2__)
#define GLINT_ISA_LEVEL avx2
#elif defined(__AVX__)
#define GLINT_ISA_LEVEL avx
#elif defined(__SSE4_1__)
#define GLINT_ISA_LEVEL sse41
#elif defined(__x86_64__) || defined(__i386__)
#define GLINT_ISA_LEVEL sse2
#else
#define GLINT_ISA_LEVEL generic
#endif

#define GLINT_ISA_CONCAT_(a, b) a##b
#define GLINT_ISA_CONCAT(a, b) GLINT_ISA_CONCAT_(a, b)
#if defined(GLINT_NO_SIMD)
#define GLINT_ISA_NAMESPACE GLINT_ISA_CONCAT(GLINT_ISA_CONCAT(isa_, GLINT_ISA_LEVEL), _nosimd)
#else
#define GLINT_ISA_NAMESPACE GLINT_ISA_CONCAT(isa_, GLINT_ISA_LEVEL)
#endif

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The SIMD instruction sets glint-render can run (--simd): the x86-64 psABI levels its
/// renderers are compiled for, each with the paths the wavefront shades at once.
enum class Simd {
  scalar,  ///< x86-64: glint's scalar kernels, one path at a time
  avx2,    ///< x86-64-v3 (AVX2, FMA): eight-wide kernels, 8 paths
  avx512,  ///< x86-64-v4 (AVX-512): 16 paths
};

/// --simd's name of `simd`.
constexpr std::string_view simd_name(Simd simd) {
  switch (simd) {
    case Simd::avx2:
      return "avx2";
    case Simd::avx512:
      return "avx512";
    case Simd::scalar:
      break;
  }
  return "scalar";
}

/// The instruction set this code was compiled for, as --simd names it: the widest whose
/// kernels it has (GLINT_NO_SIMD: scalar).
inline constexpr Simd kCompiledSimd =
#if defined(GLINT_AVX2) && defined(__AVX512F__)
    Simd::avx512;
#elif defined(GLINT_AVX2)
    Simd::avx2;
#else
    Simd::scalar;
#endif

}  // namespace glint::inline GLINT_ISA_NAMESPACE
