// glint-exr-check EXR PFM [--half]: reads an EXR written by glint-render and the PFM of the same
// render, prints the EXR's attributes (NAME (TYPE) = <VALUE>, a line each) and exits 0 when the
// pixels agree: bit for bit, or with --half within half precision (relative 2^-11, absolute
// 2^-25 below the normal halves, the largest half for what is beyond it). Status 1 otherwise.

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <variant>

#include "glint/exr/exr_image.hpp"
#include "glint/io/image_reader.hpp"

namespace {

bool agree(float exr, float pfm, bool half) {
  if (!half) return std::memcmp(&exr, &pfm, sizeof exr) == 0;
  if (std::isnan(pfm)) return std::isnan(exr);
  if (std::fabs(pfm) >= glint::kExrLargestHalf)
    return exr == std::copysign(glint::kExrLargestHalf, pfm);
  if (std::fabs(pfm) < 0x1p-14f) return std::fabs(exr - pfm) <= 0x1p-25f;
  return std::fabs(exr - pfm) <= 0x1p-11f * std::fabs(pfm);
}

}  // namespace

int main(int argc, char** argv) {
  const bool half = argc == 4 && std::strcmp(argv[3], "--half") == 0;
  if (argc != 3 && !half) {
    std::fprintf(stderr, "usage: glint-exr-check EXR PFM [--half]\n");
    return 2;
  }
  try {
    const glint::ExrImage exr = glint::read_exr(argv[1]);
    const glint::Film pfm = glint::read_pfm(argv[2]);
    for (const glint::ExrAttribute& attribute : exr.attributes) {
      std::visit(
          [&](const auto& value) {
            using T = std::decay_t<decltype(value)>;
            if constexpr (std::is_same_v<T, int>)
              std::printf("%s (int) = <%d>\n", attribute.name.c_str(), value);
            else if constexpr (std::is_same_v<T, std::string>)
              std::printf("%s (string) = <%s>\n", attribute.name.c_str(), value.c_str());
            else
              std::printf("%s (%s) = <%.17g>\n", attribute.name.c_str(),
                          std::is_same_v<T, float> ? "float" : "double", double(value));
          },
          attribute.value);
    }
    const bool exr_half = exr.pixel_type == glint::ExrPixelType::float16;
    std::printf("pixel type: %s\n", exr_half ? "half" : "float");
    if (exr_half != half) {
      std::fprintf(stderr, "glint-exr-check: %s is %s, expected %s\n", argv[1],
                   exr_half ? "half" : "float", half ? "half" : "float");
      return 1;
    }
    if (exr.film.width() != pfm.width() || exr.film.height() != pfm.height()) {
      std::fprintf(stderr, "glint-exr-check: %dx%d against %dx%d\n", exr.film.width(),
                   exr.film.height(), pfm.width(), pfm.height());
      return 1;
    }
    for (int y = 0; y < pfm.height(); ++y)
      for (int x = 0; x < pfm.width(); ++x)
        for (int c = 0; c < 3; ++c)
          if (!agree(exr.film.at(x, y)[c], pfm.at(x, y)[c], half)) {
            std::fprintf(stderr, "glint-exr-check: pixel (%d, %d) channel %d: %.9g against %.9g\n",
                         x, y, c, double(exr.film.at(x, y)[c]), double(pfm.at(x, y)[c]));
            return 1;
          }
    std::printf("pixels: %s the PFM\n", half ? "within half precision of" : "identical to");
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "glint-exr-check: %s\n", error.what());
    return 1;
  }
}
