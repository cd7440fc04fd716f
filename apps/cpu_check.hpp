#pragma once
// The CPU check of glint's programs: a program compiled for instruction sets that the CPU
// running it lacks (built with -march=native, the GLINT_NATIVE default, on a newer machine)
// exits with a message that names them and says how to build for this CPU, instead of dying
// of SIGILL at the first such instruction, wherever that happens to be.
//
// Including this header is all a program does: the check runs as a constructor of priority
// 101, before main and before every dynamic initialisation of the program's own globals (those
// of default priority), because main's first instructions may already be vector ones (GCC zeroes
// and copies local structures with AVX registers) and so may a global's initialiser. The check
// and what it calls are compiled for the baseline x86-64 (target("arch=x86-64")), and call only
// the C library, which chooses its own code by CPU at run time. Caveat: shared libraries'
// constructors and the dynamic loader run before it; they are not compiled by this build.
//
// What is checked is what the compiler was allowed to use (its macros, __AVX2__ and so on), not
// only what glint's own kernels use (GLINT_AVX2 in glint/geometry/simd.hpp): with -march=native
// the compiler vectorises any loop with those instructions, even with GLINT_NO_SIMD defined. So
// the way out is a build for another CPU (GLINT_NATIVE=OFF), not GLINT_NO_SIMD.

#include <cstddef>

#if defined(__x86_64__) || defined(__i386__)
#define GLINT_CPU_CHECK 1
#include <errno.h>  // program_invocation_short_name (GNU)
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include "glint/instruction_set.hpp"
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// An instruction set this program was compiled to use, and whether this CPU has it.
struct InstructionSet {
  const char* name;
  bool present;
};

#ifdef GLINT_CPU_CHECK
// Code that runs before the CPU is known to take the compiler's target: no vector instruction.
#define GLINT_BASELINE_CODE [[gnu::target("arch=x86-64"), gnu::noinline]]

inline constexpr std::size_t kMaxInstructionSets = 24;

/// The instruction sets the compiler was told it may use, among those __builtin_cpu_supports
/// can test in GCC 12 and clang 14, with their presence on this CPU. Fills `sets` (at least
/// kMaxInstructionSets long) and returns how many it holds.
GLINT_BASELINE_CODE inline std::size_t instruction_sets_used(
    [[maybe_unused]] InstructionSet* sets) {
  __builtin_cpu_init();  // needed before any constructor of libgcc's own has run
  std::size_t n = 0;
#define GLINT_USES(set_name, feature) \
  sets[n++] = InstructionSet{set_name, __builtin_cpu_supports(feature) != 0}
#ifdef __SSE4_1__
  GLINT_USES("SSE4.1", "sse4.1");
#endif
#ifdef __SSE4_2__
  GLINT_USES("SSE4.2", "sse4.2");
#endif
#ifdef __POPCNT__
  GLINT_USES("POPCNT", "popcnt");
#endif
#ifdef __AVX__
  GLINT_USES("AVX", "avx");
#endif
#ifdef __AVX2__
  GLINT_USES("AVX2", "avx2");
#endif
#ifdef __FMA__
  GLINT_USES("FMA", "fma");
#endif
#ifdef __BMI__
  GLINT_USES("BMI1", "bmi");
#endif
#ifdef __BMI2__
  GLINT_USES("BMI2", "bmi2");
#endif
#ifdef __AVX512F__
  GLINT_USES("AVX-512F", "avx512f");
#endif
#ifdef __AVX512VL__
  GLINT_USES("AVX-512VL", "avx512vl");
#endif
#ifdef __AVX512BW__
  GLINT_USES("AVX-512BW", "avx512bw");
#endif
#ifdef __AVX512DQ__
  GLINT_USES("AVX-512DQ", "avx512dq");
#endif
#ifdef __AVX512CD__
  GLINT_USES("AVX-512CD", "avx512cd");
#endif
#ifdef __AVX512VBMI__
  GLINT_USES("AVX-512VBMI", "avx512vbmi");
#endif
#ifdef __AVX512VBMI2__
  GLINT_USES("AVX-512VBMI2", "avx512vbmi2");
#endif
#ifdef __AVX512IFMA__
  GLINT_USES("AVX-512IFMA", "avx512ifma");
#endif
#ifdef __AVX512VNNI__
  GLINT_USES("AVX-512VNNI", "avx512vnni");
#endif
#ifdef __AVX512BITALG__
  GLINT_USES("AVX-512BITALG", "avx512bitalg");
#endif
#ifdef __AVX512VPOPCNTDQ__
  GLINT_USES("AVX-512VPOPCNTDQ", "avx512vpopcntdq");
#endif
#ifdef __GFNI__
  GLINT_USES("GFNI", "gfni");
#endif
#ifdef __VPCLMULQDQ__
  GLINT_USES("VPCLMULQDQ", "vpclmulqdq");
#endif
#undef GLINT_USES
  return n;
}

/// The message for the sets of `sets` that are missing, into `message` (of `size` bytes); false
/// when none is.
GLINT_BASELINE_CODE inline bool missing_instruction_sets_message(const InstructionSet* sets,
                                                                 std::size_t count,
                                                                 const char* program, char* message,
                                                                 std::size_t size) {
  char missing[512] = "";
  char used[512] = "";
  bool any = false;
  for (std::size_t i = 0; i < count; ++i) {
    std::strncat(used, i ? ", " : "", sizeof used - std::strlen(used) - 1);
    std::strncat(used, sets[i].name, sizeof used - std::strlen(used) - 1);
    if (sets[i].present) continue;
    std::strncat(missing, any ? ", " : "", sizeof missing - std::strlen(missing) - 1);
    std::strncat(missing, sets[i].name, sizeof missing - std::strlen(missing) - 1);
    any = true;
  }
  if (!any) return false;
  std::snprintf(message, size,
                "%s: error: this CPU lacks %s, which this %s was compiled to use (it was built "
                "for the CPU of the machine that built it, GLINT_NATIVE=ON with -march=native, "
                "the default, and uses %s).\n"
                "Build glint on this machine, or with `cmake -DGLINT_NATIVE=OFF` for any x86-64 "
                "CPU. GLINT_NO_SIMD is not enough: it turns off glint's own SIMD kernels, not the "
                "compiler's use of those instructions.\n",
                program, missing, program, used);
  return true;
}

/// Exits with status 1 and the message when this CPU lacks an instruction set the program was
/// compiled to use.
GLINT_BASELINE_CODE inline void exit_unless_cpu_supported() {
  InstructionSet sets[kMaxInstructionSets]{};
  const std::size_t count = instruction_sets_used(sets);
  static char message[2048];
  if (!missing_instruction_sets_message(sets, count, program_invocation_short_name, message,
                                        sizeof message))
    return;
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, message, std::strlen(message));
  _exit(1);
}

#if !defined(GLINT_NO_CPU_CHECK)
namespace detail {
// One per program (each includes this header in its one translation unit). Not in the
// translation units of glint-render for the wider instruction sets (GLINT_NO_CPU_CHECK), which
// run only on a CPU that has them (glint_render.cpp).
[[gnu::constructor(101), gnu::target("arch=x86-64"), gnu::used]] static void check_cpu_first() {
  exit_unless_cpu_supported();
}
}  // namespace detail
#endif

#undef GLINT_BASELINE_CODE
#endif  // GLINT_CPU_CHECK

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
