// The CPU check of glint's programs (apps/cpu_check.hpp): what it says when instruction sets
// the build uses are missing. A CPU without them is not at hand, so the message is checked on
// a made-up list, and the real list on this machine, which built the program, lacks nothing.

#include <catch2/catch.hpp>

#include <string>

#include "cpu_check.hpp"

#ifdef GLINT_CPU_CHECK

TEST_CASE("the CPU check names the missing instruction sets and the build that avoids them",
          "[cpu_check]") {
  const glint::cli::InstructionSet sets[] = {
      {"SSE4.1", true}, {"AVX", true}, {"AVX2", false}, {"FMA", false}};
  char message[2048];
  REQUIRE(glint::cli::missing_instruction_sets_message(sets, 4, "glint-render", message,
                                                       sizeof message));
  const std::string text = message;
  CHECK(
      text.starts_with("glint-render: error: this CPU lacks AVX2, FMA, which this glint-render "
                       "was compiled to use"));
  CHECK(text.find("uses SSE4.1, AVX, AVX2, FMA)") != std::string::npos);
  CHECK(text.find("cmake -DGLINT_NATIVE=OFF") != std::string::npos);
  CHECK(text.find("GLINT_NO_SIMD is not enough") != std::string::npos);
  CHECK(text.ends_with("\n"));
}

TEST_CASE("the CPU check is silent when nothing is missing", "[cpu_check]") {
  const glint::cli::InstructionSet sets[] = {{"AVX2", true}, {"FMA", true}};
  char message[2048] = "untouched";
  CHECK_FALSE(glint::cli::missing_instruction_sets_message(sets, 2, "p", message, sizeof message));
  CHECK_FALSE(glint::cli::missing_instruction_sets_message(sets, 0, "p", message, sizeof message));
  CHECK(std::string(message) == "untouched");
}

TEST_CASE("the machine that built the tests has every instruction set they use", "[cpu_check]") {
  glint::cli::InstructionSet sets[glint::cli::kMaxInstructionSets] = {};
  const std::size_t count = glint::cli::instruction_sets_used(sets);
  for (std::size_t i = 0; i < count; ++i) {
    INFO(sets[i].name);
    CHECK(sets[i].present);
  }
#if defined(__AVX2__) && defined(__FMA__)
  // GLINT_AVX2's two (glint/geometry/simd.hpp) are among those checked.
  int avx2_and_fma = 0;
  for (std::size_t i = 0; i < count; ++i)
    avx2_and_fma += std::string(sets[i].name) == "AVX2" || std::string(sets[i].name) == "FMA";
  CHECK(avx2_and_fma == 2);
#endif
}

#endif  // GLINT_CPU_CHECK
