#pragma once
// How a failed run ends: the exception being handled as an exit status and a message.

#include <string>

#include "glint/instruction_set.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// A run that failed: its exit status and what to print on stderr (ending in a newline).
struct Failure {
  int status = 1;
  std::string message;
};

/// The failure of the exception being handled (call it in a catch block): 2 with the usage for
/// a bad option, 3 for a scene this variant cannot render, 1 for a bad scene (its message is
/// already "FILE:LINE: error: PROBLEM") or any other error.
Failure current_failure(const Program& program);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
