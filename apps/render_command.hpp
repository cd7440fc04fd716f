#pragma once
// What glint-render and glint-render-mpi share, so that both take the same options and keep the
// same promises, one idea to a header:
//
//   program.hpp           the program (Program) and its options (Options); the execution model
//   command_line.hpp      the options' parsing and the usage text
//   instruction_sets.hpp  the instruction set of a run (--simd)
//   stop_signals.hpp      the stop signals
//   staged_outputs.hpp    the outputs: checked before rendering, written together or not at all
//   scene_loading.hpp     the scene loaded and the render settings
//   pass_keeper.hpp       checkpoints and the time limit, between passes
//   finish_run.hpp        the end of a run: files written, summary line, warnings, exit status
//   failure.hpp           a failed run's exit status and message
//
// None of it depends on the variant: it is compiled once, in their .cpp files (the glint-cli
// library), rather than in each of the renderer executables, one per variant. What the variant
// decides reaches it as data (Program); the variant's type and the renderer it picks are
// render_variant.hpp's, which only the programs' own translation units include.

#include "command_line.hpp"
#include "failure.hpp"
#include "finish_run.hpp"
#include "instruction_sets.hpp"
#include "pass_keeper.hpp"
#include "program.hpp"
#include "scene_loading.hpp"
#include "staged_outputs.hpp"
#include "stop_signals.hpp"
