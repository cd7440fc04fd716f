#pragma once
// The instruction set of a run. glint-render holds its renderer compiled for x86-64, x86-64-v3
// (AVX2) and x86-64-v4 (AVX-512), and runs the widest that the CPU has, or the one --simd names.
// They give the same image bit for bit: each formula is the same IEEE operations in the same
// order at every width (-ffp-contract=off; explicit fused multiply-adds, by instruction or by the
// C library).

#include <span>
#include <string>

#include "glint/instruction_set.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// Whether this CPU runs code compiled for `simd` (and the operating system saves its registers).
bool cpu_runs(glint::Simd simd);

/// The instruction set of the run: --simd's, or the widest of the program's that this CPU runs.
/// Throws UsageError for one the program was not built with or the CPU lacks.
glint::Simd run_simd(const Program& program, const Options& options);

/// "scalar, avx2, avx512".
std::string simd_list(std::span<const glint::Simd> simds);

/// What --list-simd prints: the instruction sets the program holds that this CPU runs, one a
/// line, narrowest first ("scalar\navx2\n").
std::string runnable_simd_list(const Program& program);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
