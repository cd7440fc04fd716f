#pragma once
// The material models glint ships (policy/material_model.hpp), for the estimators that build
// their Bsdf at a hit: a model's policy only declares its Bsdf, defined by the header here.

#include "glint/render/materials/microfacet_material.hpp"  // IWYU pragma: export
#include "glint/render/materials/report_material.hpp"      // IWYU pragma: export
