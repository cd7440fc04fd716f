// instruction_sets.hpp's definitions: which instruction sets the CPU runs, and the run's.

#include "instruction_sets.hpp"

#include <algorithm>
#include <string>

#include "command_line.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

std::string simd_list(std::span<const glint::Simd> simds) {
  std::string list;
  for (const glint::Simd simd : simds)
    list += (list.empty() ? "" : ", ") + std::string(glint::simd_name(simd));
  return list;
}

std::string runnable_simd_list(const Program& program) {
  std::string list;
  for (const glint::Simd simd : program.simds)
    if (cpu_runs(simd)) list += std::string(glint::simd_name(simd)) + "\n";
  return list;
}

bool cpu_runs(glint::Simd simd) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  switch (simd) {
    case glint::Simd::scalar:
      return true;
#if defined(__clang__)
    // clang 14 knows no psABI levels: the features that set x86-64-v3 and v4 apart that it can
    // test (the others, F16C, LZCNT and MOVBE, came with AVX2 in every such CPU).
    case glint::Simd::avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    case glint::Simd::avx512:
      return cpu_runs(glint::Simd::avx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
#else
    case glint::Simd::avx2:
      return __builtin_cpu_supports("x86-64-v3");
    case glint::Simd::avx512:
      return __builtin_cpu_supports("x86-64-v4");
#endif
  }
  return false;
#else
  return simd == glint::kCompiledSimd;
#endif
}

glint::Simd run_simd(const Program& program, const Options& options) {
  const auto built = [&](glint::Simd simd) {
    return std::find(program.simds.begin(), program.simds.end(), simd) != program.simds.end();
  };
  if (options.simd) {
    const std::string name(glint::simd_name(*options.simd));
    if (!built(*options.simd))
      throw UsageError{"--simd " + name + ": this program (variant " +
                       std::string(program.variant) + ") was compiled for " +
                       simd_list(program.simds) +
                       " only; glint-render, of the default variant, holds every instruction set"};
    if (!cpu_runs(*options.simd))
      throw UsageError{"--simd " + name + ": this CPU lacks the instruction set (" +
                       (*options.simd == glint::Simd::avx512 ? "x86-64-v4, AVX-512"
                                                             : "x86-64-v3, AVX2 and FMA") +
                       ")"};
    return *options.simd;
  }
  for (auto simd = program.simds.rbegin(); simd != program.simds.rend(); ++simd)
    if (cpu_runs(*simd)) return *simd;
  return program.simds.front();
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
