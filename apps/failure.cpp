// failure.hpp's definitions.

#include "failure.hpp"

#include <exception>
#include <new>

#include "command_line.hpp"
#include "glint/scene/scene_error.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

Failure current_failure(const Program& program) {
  try {
    throw;
  } catch (const UsageError& error) {
    return {2, std::string(program.name) + ": " + error.message + "\nRun '" +
                   std::string(program.name) + " --help' for the options.\n"};
  } catch (const glint::UnsupportedSceneError& error) {
    return {3, std::string(error.what()) + "\n"};
  } catch (const glint::SceneError& error) {
    return {1, std::string(error.what()) + "\n"};
  } catch (const std::bad_alloc&) {
    // What needed the memory is said where it is known (out_of_memory.hpp); elsewhere, not
    // "std::bad_alloc".
    return {1, std::string(program.name) + ": error: out of memory\n"};
  } catch (const std::exception& error) {
    return {1, std::string(program.name) + ": error: " + error.what() + "\n"};
  } catch (...) {
    return {1, std::string(program.name) + ": error: an unknown exception\n"};
  }
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
