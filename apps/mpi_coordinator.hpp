#pragma once
// Rank 0 of glint-render-mpi: it hands out the tiles of each pass (tile_scheduler.hpp), renders
// with its own threads, gathers every finished tile's sums, and reports the traffic.

#include <cstddef>
#include <cstdint>
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
  std::uint64_t tiles_moved = 0;
};

/// Rank 0: schedules the passes, renders with its own threads, gathers the sums, reports.
class Coordinator {
 public:
  Coordinator(const World& world, const glint::RenderSettings& settings, glint::PixelSums& sums,
              RankRenderer& renderer, int threads, bool resumed)
      : world_(world),
        settings_(settings),
        sums_(sums),
        renderer_(renderer),
        threads_(threads),
        grid_(settings),
        ends_(glint::pass_ends(settings.samples_per_pixel, settings.max_pass_samples)),
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
  /// One round: the messages that came, the tiles rank 0's threads finished, more for them.
  void step();

  /// The samples of the pass being rendered.
  PassSamples samples() const { return {pass_ == 0 ? 0 : ends_[pass_ - 1], ends_[pass_]}; }

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
  TileScheduler scheduler_;
  std::vector<std::uint32_t> asked_;  ///< per rank: tiles asked for, held until the next pass
  std::size_t first_pass_ = 0;
  std::size_t pass_ = 0;  ///< the pass being rendered, or the last one
  std::uint64_t samples_done_ = 0;
  std::uint64_t local_tiles_ = 0;
  Outbox outbox_;
  std::vector<PassTraffic> traffic_;  ///< per pass rendered
  PassTraffic between_passes_;        ///< requests that came between passes
  PassTraffic* counting_ = &between_passes_;
  std::vector<RankReport> reports_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
