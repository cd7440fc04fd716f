#pragma once
// What glint-render-mpi measures of itself for its report: wall-clock and CPU times, and bytes
// as text.

#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The CPU time the calling thread has used (Linux), in seconds.
inline double thread_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// "12.3 kB", "4.56 MB".
inline std::string megabytes(std::uint64_t bytes) {
  char text[32];
  if (bytes < 1000000)
    std::snprintf(text, sizeof text, "%.1f kB", double(bytes) * 1e-3);
  else
    std::snprintf(text, sizeof text, "%.2f MB", double(bytes) * 1e-6);
  return text;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
