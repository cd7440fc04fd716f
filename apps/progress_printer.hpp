#pragma once
// glint-render's progress on stderr: one line redrawn in place on a terminal, a line every tenth
// of the work otherwise (logs), each with the time elapsed and an estimate of the time left.
// The renderer reports at least every 0.1 s, so the terminal line and its estimate keep moving
// however long a tile or a pass takes; the render's last report (finished or stopped) ends the
// line.

#include <unistd.h>

#include <cstdio>
#include <string>

#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// "12.3 s", "4m05s" or "2h07m".
inline std::string format_seconds(double seconds) {
  char text[32];
  if (seconds < 60.0)
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  else if (seconds < 3600.0)
    std::snprintf(text, sizeof text, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  else
    std::snprintf(text, sizeof text, "%dh%02dm", int(seconds) / 3600, int(seconds) / 60 % 60);
  return text;
}

class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool enabled) : enabled_(enabled), terminal_(isatty(2) != 0) {}

  void operator()(const glint::RenderProgress& p) {
    if (!enabled_) return;
    const double fraction = p.fraction();
    const bool done = p.last;
    if (terminal_) {
      if (!done && p.elapsed_seconds - last_print_ < 0.1) return;
    } else {
      if (!done && int(fraction * 10) == last_decile_) return;
      last_decile_ = int(fraction * 10);
    }
    last_print_ = p.elapsed_seconds;
    std::string eta = "--";
    // From this run's share of the work: a resumed render's earlier samples took no time here.
    const std::uint64_t total_here = p.samples_total - p.samples_at_start;
    const double fraction_here =
        total_here ? double(p.samples_done - p.samples_at_start) / double(total_here) : 1.0;
    if (fraction_here > 0.0)
      eta = format_seconds(p.elapsed_seconds * (1.0 - fraction_here) / fraction_here);
    std::fprintf(stderr, "%s[%3d%%] %s elapsed, ETA %s   %s", terminal_ ? "\r" : "",
                 int(fraction * 100.0), format_seconds(p.elapsed_seconds).c_str(), eta.c_str(),
                 terminal_ && !done ? "" : "\n");
    std::fflush(stderr);
    // The reader of stderr went away (`glint-render ... 2>&1 | head`; SIGPIPE is ignored, so
    // the write failed with EPIPE): progress is a side channel, the render goes on without it.
    if (std::ferror(stderr)) {
      enabled_ = false;
      std::clearerr(stderr);
    }
  }

 private:
  bool enabled_;
  bool terminal_;
  double last_print_ = -1.0;
  int last_decile_ = -1;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
