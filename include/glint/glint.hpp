#pragma once
// Everything glint offers, in one include.

#include "glint/config.hpp"
#include "glint/io/image_output.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/render/renderer.hpp"
#include "glint/scene/scene.hpp"
#include "glint/variants.hpp"
