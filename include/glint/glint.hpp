#pragma once
// Everything glint offers, in one include.
//
// Compile with -ffp-contract=off: glint's CMake target (glint::glint) adds it, and the images
// are the same bit for bit on every machine and build only with it. Without the target, a
// compiler may fuse a * b + c into one FMA (GCC by default, Clang within an expression), and the
// images move by a few ulps; glint::multiply_add_is_fused() (glint/fp_contract.hpp) tells a
// program whether its own translation unit does.

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/fp_contract.hpp"
#include "glint/generate/random_scene.hpp"
#include "glint/image/film.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/image/splat_sums.hpp"
#include "glint/image/texture.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/input_file.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/io/texture_reader.hpp"
#include "glint/render/bidirectional_execution.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/render/work_estimate.hpp"
#include "glint/scene/scene.hpp"
#include "glint/variants.hpp"
