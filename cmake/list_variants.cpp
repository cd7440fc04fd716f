// Prints glint's named variants (glint::variants::all), one per line, for CMake and the
// scripts: "variant<TAB>NAME<TAB>same|different<TAB>DESCRIPTION", then "default<TAB>NAME", then
// "renderer<TAB>NAME<TAB>scalar|wavefront<TAB>CLASS" for each execution model a variant renders
// with: scalar is Renderer<V> (one path at a time), whose execution model is the class template
// CLASS (what its estimator names); wavefront is WavefrontRenderer<V>. Then
// "estimator<TAB>NAME" for each variant glint-render holds (glint::variants::render_estimators),
// and "blind_spot<TAB>NAME": the one it chooses where the path tracer is blind.
// Compiled and run at configure time (cmake/GlintVariants.cmake), so that variants.hpp stays
// the only list of variants.

#include <cstdio>
#include <string>
#include <type_traits>

#include "glint/render/bidirectional_execution.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/scalar_execution.hpp"
#include "glint/render/wavefront/wavefront_execution.hpp"
#include "glint/variants.hpp"

/// The class template of Renderer<V>'s execution model, as C++ names it.
template <typename V>
const char* execution_template() {
  using E = typename V::estimator::template execution<V>;
  if constexpr (std::is_same_v<E, glint::ScalarExecution<V>>)
    return "glint::ScalarExecution";
  else if constexpr (std::is_same_v<E, glint::LightTracingExecution<V>>)
    return "glint::LightTracingExecution";
  else if constexpr (std::is_same_v<E, glint::BidirectionalExecution<V>>)
    return "glint::BidirectionalExecution";
  else if constexpr (std::is_same_v<E, glint::VertexMergingExecution<V>>)
    return "glint::VertexMergingExecution";
  else
    static_assert(std::is_same_v<E, glint::ScalarExecution<V>>,
                  "an execution model list_variants.cpp does not know: name it here");
}

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
    std::printf("renderer\t%s\tscalar\t%s\n", name.c_str(), execution_template<V>());
    if constexpr (glint::WavefrontConfig<V>)
      std::printf("renderer\t%s\twavefront\tglint::WavefrontExecution\n", name.c_str());
  });
  [&]<typename... V>(std::type_identity<std::tuple<V...>>) {
    (std::printf("estimator\t%s\n", std::string(V::info.name).c_str()), ...);
  }(std::type_identity<glint::variants::render_estimators>{});
  std::printf("blind_spot\t%s\n",
              std::string(glint::variants::blind_spot_variant::info.name).c_str());
}
