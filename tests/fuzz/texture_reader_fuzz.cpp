// libFuzzer target for the texture decoder (io/texture_reader.hpp): on bytes nobody vouches for,
// decode_texture returns a texture within glint's image limits, every texel finite and
// non-negative, or throws ImageReadError; it never crashes or overflows (ASan and UBSan watch
// glint's side; the decoder is Debian's stb_image, built without them).
//
//   build-fuzz/tests/fuzz/glint-texture-reader-fuzz -max_len=65536 tests/fuzz/texture-corpus

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "glint/io/texture_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const glint::Texture texture = glint::decode_texture(bytes, "fuzz", "fuzz");
    if (texture.width() < 1 || texture.height() < 1 ||
        std::int64_t{texture.width()} * texture.height() > glint::limits::max_image_pixels)
      std::abort();
    for (const glint::Color& c : texture.texels())
      if (!(c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f) || !std::isfinite(c.r) ||
          !std::isfinite(c.g) || !std::isfinite(c.b))
        std::abort();
  } catch (const glint::ImageReadError&) {
  }
  return 0;
}
