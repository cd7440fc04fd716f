#pragma once
// Whether the code that includes glint fuses multiplies and adds. glint's images are the same
// bit for bit on every machine and build because each formula is the same IEEE operations in the
// same order: glint's CMake target compiles with -ffp-contract=off. A program that includes the
// headers without the target (its own flags, GCC's default -ffp-contract=fast, Clang's default
// on) may have a * b + c fused into one FMA instruction where the target CPU has one, which
// rounds once instead of twice: its images then differ in the last bits from glint-render's,
// and may differ between two of its own translation units. This tells it so.

namespace glint {

/// True where the translation unit that calls it contracts a * b + c into a fused multiply-add.
/// Internal linkage on purpose: each translation unit gets its own copy, compiled with its own
/// flags, so the answer is about the caller's code, never a copy the linker chose from
/// elsewhere. The operands are read from volatile objects, so the compiler cannot fold the
/// arithmetic: a = 1 + 2^-12 squared is 1 + 2^-11 + 2^-24, whose last term a float product
/// rounds away (a tie, to even) and a fused multiply-add keeps, so a * a - (1 + 2^-11) is 0
/// computed in two roundings and 2^-24 in one.
[[maybe_unused]] static bool multiply_add_is_fused() noexcept {
  volatile float va = 1.0f + 0x1p-12f;
  volatile float vc = -(1.0f + 0x1p-11f);
  const float a = va, c = vc;
  return a * a + c != 0.0f;
}

}  // namespace glint
