#pragma once
// Sampler policies: where the renderer's random numbers come from.
//
// Every sampler is a pure function of (pixel, sample index, seed, dimension): `start` forgets
// everything about the previous sample, so the image does not depend on which thread renders
// which pixel or in what order. A "dimension" is one request, 1D or 2D, counted from start();
// the stratified and low-discrepancy samplers spread the samples of one pixel evenly over each
// dimension, which helps wherever request d serves the same purpose in every sample (the
// antialiasing pair first, then the bounces in order).
//
// One header per sampler under policy/sampler/; this one includes them all.

#include "glint/policy/sampler/hybrid_sobol.hpp"
#include "glint/policy/sampler/independent.hpp"
#include "glint/policy/sampler/sobol.hpp"
#include "glint/policy/sampler/stratified.hpp"
