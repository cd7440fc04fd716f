// The planted offender of `build: each named renderer is compiled once`: a file outside
// glint-renderers that uses a named variant's execution model without glint_renderers.hpp, as a
// program that compiles a renderer again does. The address of a static member is enough for the
// object file to define a symbol of ScalarExecution<variants::report>, which the check must find.
#include "glint/render/scalar_execution.hpp"
#include "glint/variants.hpp"

const char* const* glint_planted_renderer_member() {
  return &glint::ScalarExecution<glint::variants::report>::kName;
}
