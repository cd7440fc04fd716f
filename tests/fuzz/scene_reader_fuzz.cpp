// libFuzzer target for the scene reader. The reader's contract on untrusted text: it returns a
// valid description or throws SceneError, and never crashes, hangs, reads out of bounds or
// overflows (ASan and UBSan watch the last three). Anything else escaping is a finding.
//
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DGLINT_BUILD_FUZZERS=ON
//   cmake --build build-fuzz --target glint-scene-reader-fuzz
//   build-fuzz/tests/fuzz/glint-scene-reader-fuzz -dict=tests/fuzz/scene.dict \
//       -max_total_time=120 tests/fuzz/corpus

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "glint/io/scene_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const glint::SceneDescription scene = glint::read_scene_text(text, "fuzz");
    // What the reader accepts must satisfy its own postcondition.
    glint::validate(scene);
    for (const glint::SphereDescription& sphere : scene.spheres)
      if (!(sphere.radius > 0.0f) || sphere.line < 1) std::abort();
  } catch (const glint::SceneError& error) {
    // Errors point inside the input (or at no line at all).
    if (error.line() < 0 || static_cast<std::size_t>(error.line()) > size + 1) std::abort();
  }
  return 0;
}
