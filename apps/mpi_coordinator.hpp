#pragma once
// Rank 0 of glint-render-mpi: it hands out the tiles of each pass (tile_scheduler.hpp), renders
// with its own threads, gathers every finished tile's sums and, after each pass, every rank's
// splats, and reports the traffic. A variant with a light phase (vertex merging) has each pass
// handed out one sample index at a time: every rank runs that index's light phase before its
// first tile of it (Renderer::render_tiles), and the next index's tiles wait for the last one's.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/tile_grid.hpp"
#include "mpi_messages.hpp"
#include "mpi_rank_renderer.hpp"
#include "mpi_world.hpp"
#include "tile_scheduler.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// Bytes and messages of one pass, as rank 0 sees them (every message goes to or from it).
struct PassTraffic {
  double seconds = 0.0;
  std::uint64_t bytes_in = 0, messages_in = 0;    ///< requests and finished tiles' sums
  std::uint64_t bytes_out = 0, messages_out = 0;  ///< assignments and moved tiles' sums
  std::uint64_t sums_back = 0, sums_moved = 0;    ///< of which sums, bytes
  std::uint64_t splats_in = 0;  ///< the other ranks' splats, summed into rank 0's, bytes
  std::uint64_t tiles_moved = 0;
};

/// Rank 0: schedules the passes, renders with its own threads, gathers the sums, reports.
class Coordinator {
 public:
  /// `light_phase`: the variant's tiles of a sample index follow that index's light phase
  /// (kExecutionHasLightPhase); with splats (sums.has_splats()), every rank's are summed into
  /// `sums` after each pass.
  Coordinator(const World& world, const glint::RenderSettings& settings, glint::PixelSums& sums,
              RankRenderer& renderer, int threads, bool resumed, bool light_phase)
      : world_(world),
        settings_(settings),
        sums_(sums),
        renderer_(renderer),
        threads_(threads),
        grid_(settings),
        ends_(glint::pass_ends(settings.samples_per_pixel, settings.max_pass_samples)),
        steps_(light_phase ? sample_indices(settings.samples_per_pixel) : ends_),
        scheduler_(grid_.count, world.size, !resumed),
        asked_(std::size_t(world.size), 0) {}

  /// Renders the passes from `first_pass` on, under `control`, as Renderer::render does.
  glint::RenderResult render(const glint::RenderControl& control, int first_pass);

  /// "3 ranks x 2 threads", or "3 ranks, 5 threads (2+2+1)" when they differ.
  std::string workers() const;

  /// The lines after the summary: idle time per rank and bytes sent; with `verbose`, a line
  /// per pass and per rank.
  std::string report_lines(bool verbose) const;

 private:
  /// 1, 2, ..., samples: the ends of steps of one sample index each.
  static std::vector<int> sample_indices(int samples) {
    std::vector<int> ends(static_cast<std::size_t>(samples));
    for (std::size_t i = 0; i < ends.size(); ++i)
      ends[i] = int(i) + 1;
    return ends;
  }

  /// Hands out the tiles of step `step_` and returns once every one has finished.
  void render_step(const std::function<void()>& report);

  /// One round: the messages that came, the tiles rank 0's threads finished, more for them.
  void poll_round();

  /// Every rank's splats of the pass, added to rank 0's sums.
  void gather_splats();

  /// The samples of the step being rendered.
  PassSamples samples() const { return {step_ == 0 ? 0 : steps_[step_ - 1], steps_[step_]}; }

  /// A message from another rank: finished tiles and a request, or its failure.
  void receive(const Message& message);

  /// Tiles for a rank that asked for `want`, or its request held until the next pass.
  void hand_out(int rank, std::uint32_t want);

  /// Tells every other rank that the render is over, once each has asked for more: then no
  /// message of theirs is left unreceived.
  void stop_workers();

  const World& world_;
  const glint::RenderSettings& settings_;
  glint::PixelSums& sums_;
  RankRenderer& renderer_;
  const int threads_;
  const glint::TileGrid grid_;
  const std::vector<int> ends_;
  /// The sample counts at which the tiles of all ranks meet: the passes' ends, or every sample
  /// index with a light phase.
  const std::vector<int> steps_;
  TileScheduler scheduler_;
  std::vector<std::uint32_t> asked_;  ///< per rank: tiles asked for, held until the next pass
  std::size_t first_pass_ = 0;
  std::size_t pass_ = 0;  ///< the pass being rendered, or the last one
  std::size_t step_ = 0;  ///< the step being rendered, or the last one
  std::uint64_t samples_done_ = 0;
  std::uint64_t local_tiles_ = 0;
  Outbox outbox_;
  std::vector<PassTraffic> traffic_;  ///< per pass rendered
  PassTraffic between_passes_;        ///< requests that came between passes
  PassTraffic* counting_ = &between_passes_;
  std::vector<RankReport> reports_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
