#pragma once
// The command line of glint-render and glint-render-mpi: its parsing into Options, the usage
// text (the one list of the options, which --help prints and an unknown option's hint reads),
// and the error of a bad command line.

#include <functional>
#include <string>
#include <string_view>

#include "glint/instruction_set.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// A bad command line: status 2, the message and where to find the options (--help).
struct UsageError {
  std::string message;
};

/// A program's own option: given the argument and a way to take its value, says whether it
/// was one (and took it), or throws UsageError.
using ExtraOption =
    std::function<bool(std::string_view arg, const std::function<std::string_view()>& value)>;

Options parse_options(int argc, char** argv, const Program& program, const ExtraOption& extra = {});

/// What --help prints on stdout.
std::string help_text(const Program& program);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
