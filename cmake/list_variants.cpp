// Prints glint's named variants (glint::variants::all), one per line, for CMake and the
// scripts: "variant<TAB>NAME<TAB>same|different<TAB>DESCRIPTION", then "default<TAB>NAME", then
// "renderer<TAB>NAME<TAB>scalar|wavefront" for each execution model a variant renders with.
// Compiled and run at configure time (cmake/GlintVariants.cmake), so that variants.hpp stays
// the only list of variants.

#include <cstdio>
#include <string>

#include "glint/render/wavefront/wavefront_execution.hpp"
#include "glint/variants.hpp"

int main() {
  glint::variants::for_each([]<typename V>() {
    const glint::VariantInfo& info = V::info;
    std::printf("variant\t%s\t%s\t%s\n", std::string(info.name).c_str(),
                info.same_image_as_report ? "same" : "different",
                std::string(info.description).c_str());
  });
  std::printf("default\t%s\n", std::string(glint::variants::default_variant::info.name).c_str());
  glint::variants::for_each([]<typename V>() {
    const std::string name(V::info.name);
    std::printf("renderer\t%s\tscalar\n", name.c_str());
    if constexpr (glint::WavefrontConfig<V>) std::printf("renderer\t%s\twavefront\n", name.c_str());
  });
}
