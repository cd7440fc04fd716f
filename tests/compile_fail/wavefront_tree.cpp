// Must NOT compile: `report` follows every lobe (a tree of rays per sample), which the
// wavefront renderer cannot; the test checks for WavefrontExecution's message.
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"

int main() {
  const glint::Scene* scene = nullptr;
  (void)glint::WavefrontRenderer<glint::variants::report>::render(*scene, glint::RenderSettings{});
}
