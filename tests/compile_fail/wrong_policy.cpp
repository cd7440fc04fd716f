// Must NOT compile: int is not a Fresnel. The test checks that the compiler's message
// names the violated concept.
#include "glint/config.hpp"

using broken = glint::Config<glint::IndependentSampler, glint::TreePathTracing, int,
                             glint::GaussianAntialiasing, glint::BuiltinShading>;
broken::fresnel* use = nullptr;
int main() {}
