// Slice 0 of the renderers the render tests run (renderer_types.hpp).
#include "renderer_slice.hpp"

template std::vector<glint_test::RenderFunction> glint_test::slice_renderers<0>();
