#pragma once
// The stop signals of glint-render and glint-render-mpi. The first stop signal stops after the
// current pass and writes the image of the passes done; a second one removes the temporaries
// being written and exits at once: another signal, or the same one a second or more after the
// first (supervisors such as `timeout` send the process and its process group one copy each),
// except SIGXCPU, which the kernel repeats every second past a soft CPU-time limit.

#include <signal.h>

#include <atomic>
#include <span>
#include <string>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// Set by the first stop signal: the render's RenderControl::stop.
extern std::atomic<bool> stop_requested;

/// Makes `signals` (at most 8) stop the render; `program` names the message of a second one.
void install_signal_handlers(const char* program, std::span<const int> signals);

/// The first stop signal received, or 0.
int received_stop_signal();

/// "SIGINT", "SIGTERM", ...: a stop signal's name, for messages.
const char* signal_name(int signal);

/// Holds the stop signals back for its lifetime, so that a second signal's handler never sees
/// the list of temporaries half-updated or a set of outputs half-renamed.
class BlockStopSignals {
 public:
  BlockStopSignals();
  ~BlockStopSignals();
  BlockStopSignals(const BlockStopSignals&) = delete;
  BlockStopSignals& operator=(const BlockStopSignals&) = delete;

 private:
  sigset_t previous_;
};

/// Adds a temporary file to those a second signal removes (at most 5: the PNG, the PFM, the
/// EXR, the stats and the checkpoint); false, and nothing added, for a path too long to keep. Call
/// with the stop signals blocked.
bool note_temporary(const std::string& path);

/// Forgets the temporaries noted, once they are renamed or removed.
void forget_temporaries();

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
