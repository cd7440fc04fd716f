// mpi_worker.hpp's definitions.

#include "mpi_worker.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "glint/render/tile_grid.hpp"
#include "mpi_messages.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

void serve(const World& world, const glint::RenderSettings& settings, RankRenderer& renderer,
           glint::PixelSums& sums, int threads) {
  const glint::TileGrid grid(settings);
  TileQueue& queue = renderer.queue();
  Outbox outbox;
  bool asked = false;  // a request is waiting for rank 0's answer
  std::uint64_t tiles = 0;
  const auto fail = [&](const std::string& message) {
    // Rank 0 prints it and ends the run; this rank waits for that, or does it itself.
    const std::string text = failure_report(world, message);
    MPI_Send(text.data(), int(text.size()), MPI_CHAR, 0, kTagFailed, MPI_COMM_WORLD);
    std::this_thread::sleep_for(std::chrono::seconds(10));
    abort_run(describe_failure(world, world.rank, text));
  };
  try {
    for (bool stop = false; !stop;) {
      outbox.progress();
      while (std::optional<Message> message = poll()) {
        if (message->tag == kTagStop) {
          stop = true;
          break;
        }
        if (message->tag == kTagSplats && sums.has_splats()) {
          // Every tile of the pass has finished here (rank 0 has them all): no thread splats.
          sum_splats(world.rank, sums.splats());
          continue;
        }
        if (message->tag != kTagAssign) throw std::runtime_error("an unexpected message");
        Unpacker in(message->bytes);
        const auto samples = in.get<PassSamples>();
        const auto count = in.get<std::uint32_t>();
        for (std::uint32_t i = 0; i < count; ++i) {
          const auto tile = in.get<std::uint32_t>();
          const auto with_sums = in.get<std::uint8_t>();
          if (tile >= grid.count) throw std::runtime_error("a tile out of range");
          if (with_sums) in.get_sums(grid.tile(tile), sums);
          queue.add({tile, samples.first, samples.last, 0});
        }
        if (!in.done()) throw std::runtime_error("a message longer than its fields");
        asked = false;
      }
      if (stop) break;
      if (const std::optional<Failure> failure = renderer.failed()) fail(failure->message);
      const std::vector<glint::TileWork> done = queue.take_finished();
      const std::size_t queued = queue.queued();
      const auto want = std::uint32_t(asked ? 0 : tiles_wanted(queued, threads));
      if (!done.empty() || want > 0) {
        Packer out;
        out.put(want);
        out.put(std::uint32_t(done.size()));
        for (const glint::TileWork& work : done) {
          out.put(std::uint32_t(work.tile));
          out.put(PassSamples{work.first_sample, work.last_sample});
          out.put_sums(grid.tile(work.tile), sums);
        }
        outbox.send(0, kTagWork, out.take());
        asked = asked || want > 0;
        tiles += done.size();
      }
      queue.wait(kPollInterval);
    }
  } catch (const std::exception& error) {
    fail(std::string("error: ") + error.what());
  }
  outbox.flush();
  renderer.finish();
  if (const std::optional<Failure> failure = renderer.failed()) fail(failure->message);
  gather_reports(world, renderer, tiles);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
