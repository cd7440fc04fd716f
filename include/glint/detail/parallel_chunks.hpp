#pragma once
// Building a scene on every core: work(begin, end) over [0, count) in chunks taken from one
// atomic counter, by the calling thread and up to hardware_concurrency - 1 others. For loops
// whose iterations are independent and whose result does not depend on which thread ran
// which chunk (each writes its own elements), so a scene built on any number of cores is the
// same. If threads cannot be started, the calling thread does all the work.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::detail {

/// `work` must not throw (record failures per element and report them afterwards). `cores`:
/// how many threads at most, the calling one included (0: as many as there are cores).
template <typename Work>
void parallel_chunks(std::size_t count, std::size_t chunk, std::size_t cores, const Work& work) {
  chunk = std::max<std::size_t>(chunk, 1);
  std::atomic<std::size_t> next{0};
  const auto run = [&] {
    for (std::size_t begin = next.fetch_add(chunk, std::memory_order_relaxed); begin < count;
         begin = next.fetch_add(chunk, std::memory_order_relaxed))
      work(begin, std::min(count, begin + chunk));
  };
  const std::size_t chunks = (count + chunk - 1) / chunk;
  if (cores == 0) cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t helpers = std::min<std::size_t>(cores - 1, chunks > 0 ? chunks - 1 : 0);
  std::vector<std::jthread> threads;
  threads.reserve(helpers);
  for (std::size_t t = 0; t < helpers; ++t) {
    try {
      threads.emplace_back(run);
    } catch (const std::system_error&) {
      break;  // fewer threads: the ones started and this one share the work
    }
  }
  run();
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::detail
