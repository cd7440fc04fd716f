#pragma once
// The error type for bad scenes, whether they come from a file or from library calls. Its
// message has the compiler-style form "SOURCE:LINE: error: PROBLEM" so that editors and
// terminals can jump to the offending line.

#include <string>

#include "glint/error.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class SceneError : public Error {
 public:
  /// line 0 means "no particular line" (a problem with the scene as a whole).
  SceneError(std::string source, int line, const std::string& problem)
      : Error(format(source, line, problem)),
        source_(std::move(source)),
        line_(line),
        problem_(problem) {}

  const std::string& source() const noexcept { return source_; }
  int line() const noexcept { return line_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  static std::string format(const std::string& source, int line, const std::string& problem) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on `"literal" + std::string`.
    std::string text = source.empty() ? std::string("<scene>") : source;
    if (line > 0) text.append(":").append(std::to_string(line));
    text.append(": error: ").append(problem);
    return text;
  }

  std::string source_;
  int line_;
  std::string problem_;
};

/// A valid scene that asks for something the chosen renderer variant was built without (a
/// shading kind its SphereShading policy does not support). Another variant can render it.
class UnsupportedSceneError : public SceneError {
 public:
  using SceneError::SceneError;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
