#pragma once
// Everything glint offers, in one include.

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/generate/random_scene.hpp"
#include "glint/image/film.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/render/work_estimate.hpp"
#include "glint/scene/scene.hpp"
#include "glint/variants.hpp"
