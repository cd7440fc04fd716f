// Must NOT compile: a material model whose Bsdf has no pdf. The estimators check their Config's
// Bsdf against the concept, and the message names it.
#include <string_view>

#include "glint/render/path_tracer.hpp"
#include "glint/variants.hpp"

template <typename C, typename F>
class NoDensity {
 public:
  NoDensity(const glint::BasicSurfaceInteraction<F>&, const glint::Vec3For<F>&, glint::MaskFor<F>) {
  }
  glint::MaskFor<F> scatters() const { return true; }
  glint::MaskFor<F> has_density() const { return true; }
  template <glint::Transport mode, typename Draws>
  glint::BasicScatterSample<F> sample(Draws&, glint::MaskFor<F>) const {
    return {};
  }
  template <glint::Transport mode = glint::Transport::radiance>
  glint::Vec3For<F> evaluate(const glint::Vec3For<F>&) const {
    return {};
  }
};

struct WithoutDensity {
  static constexpr std::string_view name = "a material without a pdf";
  template <typename C, typename F>
  using bsdf = NoDensity<C, F>;
  static bool supports(const glint::Material&) { return true; }
};

using broken = glint::variants::fast::with_material_model<WithoutDensity>;
template class glint::ChainEstimator<broken>;
int main() {}
