// glint-render-mpi: glint-render on several processes, with MPI (`mpirun -n N glint-render-mpi
// SCENE [options]`), writing the image glint-render writes with the same options, bit for bit.
// It holds glint-render's estimators and chooses among them as glint-render does
// (estimator_choice.hpp: --estimator, the checkpoint resumed, or the scene), rank 0 for every
// rank; each with its wavefront renderer where it has one, its scalar one with --scalar
// (render_variant.hpp's with_renderer); and like glint-render it is compiled once per
// instruction set where GLINT_RENDER_SIMD_SETS says so: main (x86-64) initialises MPI, reads the
// options and runs the chosen set's entry, glint_render_mpi_<set>, which reads them again and
// renders.
//
// Every rank renders with all its threads (render_tiles); rank 0 also schedules,
// gathers and writes. The render is glint-render's passes. A pixel's sum must grow sample by
// sample in index order across passes, so whoever renders a tile in a pass starts from the sums
// that tile had after the pass before. Rank 0 hands out tiles (tile_scheduler.hpp): each rank
// asks for a batch when its threads have one tile each or fewer left in hand, and gets back
// first the tiles it rendered in the pass before, whose sums it holds, so that nothing but the
// tile numbers is sent; once none is left, it takes tiles from the rank with the most left,
// and rank 0 sends their sums with them. Each finished tile's sums go back to rank 0 with the
// next request, and an estimator's splats (light paths joined to the camera, landing on any
// pixel) are summed from every rank into rank 0's after each pass, so that after every pass
// rank 0 has the whole image: for the progress, a stop after any pass, checkpoints (the same
// file as glint-render's) and the outputs. The ranks meet only at the end of each pass, when
// rank 0 holds back their requests until the next one; with vertex merging also at the end of
// each sample index, whose light phase every rank runs for itself (the same light paths, from
// the same keys) before its tiles of that index.
//
// MPI is called from each rank's main thread only (MPI_THREAD_FUNNELED), which polls it and
// sleeps on the rendering threads' queue in between: a blocking MPI call would spin a core
// that the rendering threads need.
//
// This file is the program: its options, its run, and the renderer of its variant (the one
// translation unit that names it). The rest is in mpi_*.hpp: the wire format (mpi_messages), the
// ranks agreeing before the render (mpi_agreement), the scene's way to the ranks (mpi_scene), a
// rank's rendering threads (mpi_rank_renderer), rank 0's scheduling (mpi_coordinator) and the
// other ranks' work (mpi_worker).

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "estimator_choice.hpp"
#include "glint/glint.hpp"
#include "load_progress.hpp"
#include "mpi_agreement.hpp"
#include "mpi_coordinator.hpp"
#include "mpi_measures.hpp"
#include "mpi_rank_renderer.hpp"
#include "mpi_scene.hpp"
#include "mpi_worker.hpp"
#include "mpi_world.hpp"
#include "out_of_memory.hpp"
#include "progress_printer.hpp"
#include "render_command.hpp"
#include "render_variant.hpp"

namespace {

using glint::cli::Variant;
namespace cli = glint::cli;
namespace mpi = glint::cli::mpi;

constexpr cli::Program kProgram{
    "glint-render-mpi",
    "mpirun -n N ",
    R"(Renders SCENE (a glint scene file) on N processes (MPI ranks, on one machine or several)
with the estimator glint-render would choose, and writes the image glint-render writes with the
same options, bit for bit, whatever the number of ranks and threads. Rank 0 reads SCENE and
sends it to the others, hands out the tiles, prints the progress and writes the outputs (paths
are rank 0's).)",
    R"(  --threads N         rendering threads per rank (default: the CPUs the rank may run on;
                      mpirun binds each rank to one core unless given --bind-to none)
)",
    R"(  --scene-everywhere  every rank reads SCENE itself, at the same path (a shared file
                      system), instead of receiving rank 0's copy
  --verbose           after the summary, a line per pass (time, bytes sent) and per rank
                      (threads, tiles, idle time)
)",
    R"(Progress with an estimated time left goes to stderr while rendering, then one summary line
naming the ranks and threads, and a line with each rank's idle time and the bytes sent.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGALRM or SIGXCPU (a batch system's or a CPU-time
limit's) stops after the current pass and writes the image of the passes done, saying how many samples per pixel it holds; a second one exits at once (the
same signal again within a second is the same stop: timeout and other supervisors signal
the process and then its process group).
Open MPI's mpirun passes SIGUSR1 on to every rank as it is, but answers SIGINT and SIGTERM by
sending SIGTERM to every rank and SIGKILL about a second later: the image is then written only
if the current pass ends in that time. To stop a long pass, send mpirun SIGUSR1.
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written, after every rank has ended its work: a rank that dies
makes mpirun end the run, and no image is written.
Exit status (rank 0's, which mpirun returns unless it was signalled itself): 0 on success
(--time-limit included), 1 for a bad scene, an unwritable output, a checkpoint that cannot be
resumed or written at the end (the images are written first), a CPU without an instruction set this build uses or a rank that failed, 2 for bad
options, 3 for a valid scene that this variant cannot render (a shading kind it was built
without), 128 + the signal's number when a signal stopped the render (138 for SIGUSR1).
)",
    Variant::info.name,
    cli::kVariantHasWavefront,
    cli::kProgramSimds,
    cli::kVariantWavefrontLanes};

// SIGUSR1 too: mpirun forwards it as it is, without killing the ranks a second later. SIGALRM
// and SIGXCPU are what batch systems and a CPU-time limit send to say that time is up.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGALRM, SIGXCPU};

struct MpiOptions {
  bool scene_everywhere = false;
  bool verbose = false;
  std::optional<std::size_t> estimator;  ///< --estimator: an index in ProgramVariants; none: auto
};

#if defined(GLINT_RENDER_SIMD_SETS)
}  // namespace
// Each defined by this file compiled for its instruction set (GLINT_ISA_LEVEL): run() there, for
// a rank of MPI_COMM_WORLD already initialised.
extern "C" int glint_render_mpi_sse2(int rank, int size, const char* host, int argc, char** argv);
extern "C" int glint_render_mpi_avx2(int rank, int size, const char* host, int argc, char** argv);
extern "C" int glint_render_mpi_avx512(int rank, int size, const char* host, int argc, char** argv);
namespace {
#endif

/// The command line, read the same by every rank: its status when it ends the run at once (a
/// bad option, --help), printed by rank 0 alone.
std::optional<int> read_command_line(const mpi::World& world, int argc, char** argv,
                                     const cli::Program& program, cli::Options& options,
                                     MpiOptions& mpi_options, glint::Simd& simd) {
  const auto own_option = [&](std::string_view arg,
                              const std::function<std::string_view()>& value) {
    if (arg == "--scene-everywhere") return mpi_options.scene_everywhere = true;
    if (arg == "--verbose") return mpi_options.verbose = true;
    if (arg == "--estimator" && cli::kHoldsEstimators) {
      mpi_options.estimator = cli::parse_estimator(arg, value());
      return true;
    }
    return false;
  };
  try {
    options = cli::parse_options(argc, argv, program, own_option);
    simd = cli::run_simd(program, options);
  } catch (const cli::UsageError&) {
    const cli::Failure failure = cli::current_failure(program);
    if (world.rank == 0) std::cerr << failure.message;
    return failure.status;
  }
  if (options.help) {
    if (world.rank == 0) std::cout << cli::help_text(program);
    return 0;
  }
  if (options.list_simd) {
    if (world.rank == 0) std::cout << cli::runnable_simd_list(program);
    return 0;
  }
  return std::nullopt;
}

/// Runs the program compiled for `simd`, another instruction set than this translation unit's:
/// each rank runs the renderer of the instruction set it chose, and all give the same image.
int run_other_simd(const mpi::World& world, const cli::Program& program, glint::Simd simd, int argc,
                   char** argv) {
#if defined(GLINT_RENDER_SIMD_SETS)
  const char* host = world.host.c_str();
  switch (simd) {
    case glint::Simd::scalar:
      return glint_render_mpi_sse2(world.rank, world.size, host, argc, argv);
    case glint::Simd::avx2:
      return glint_render_mpi_avx2(world.rank, world.size, host, argc, argv);
    case glint::Simd::avx512:
      return glint_render_mpi_avx512(world.rank, world.size, host, argc, argv);
  }
#endif
  if (world.rank == 0)
    std::cerr << program.name << ": error: no renderer for --simd " << glint::simd_name(simd)
              << " in this program\n";
  return 1;
}

/// What every rank holds once the scene is loaded.
struct SceneOnRanks {
  std::optional<glint::Scene> scene;
  glint::RenderSettings settings;
  std::uint64_t hash = 0;  ///< of the file's bytes, for checkpoints and --scene-everywhere
  mpi::LoadTimes times;
};

/// Reads the scene (rank 0, or every rank with --scene-everywhere), sends it to every rank, and
/// builds it there with the run's settings; the status of a failure on any rank, else 0.
int load_scene_on_ranks(const mpi::World& world, const cli::Program& program,
                        const cli::Options& options, const MpiOptions& mpi_options,
                        SceneOnRanks& loaded) {
  const bool everywhere = mpi_options.scene_everywhere;
  const mpi::Clock::time_point start = mpi::Clock::now();
  mpi::LoadTimes& times = loaded.times;
  cli::LoadProgress loading(world.rank == 0 && !options.quiet, options.scene);
  std::string text;
  if (int status = mpi::agree(world, mpi::attempt(program, [&] {
                                text = mpi::scene_text(world, options, everywhere, loading, start,
                                                       times);
                              })))
    return status;
  times.sent = mpi::seconds_since(start);
  times.bytes = text.size();
  if (everywhere || (world.rank == 0 && (options.checkpoint || options.resume)))
    loaded.hash = cli::scene_text_hash(text);
  std::uint64_t rank0_hash = loaded.hash;
  if (everywhere) MPI_Bcast(&rank0_hash, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (int status = mpi::agree(
          world, mpi::attempt(program, [&] {
            if (rank0_hash != loaded.hash)
              throw glint::Error("cannot render " + options.scene +
                                 ": its bytes here differ from rank 0's");
            loaded.scene.emplace(cli::parse_and_build(loading, std::move(text), options.scene));
            times.built = mpi::seconds_since(start);
            loaded.settings = cli::render_settings(options, *loaded.scene);
            if (!options.threads)
              loaded.settings.threads = std::min(mpi::cpus_available(), glint::limits::max_threads);
          })))
    return status;
  // Every rank reads the images the spheres show from its own file system: they must be rank
  // 0's, or the ranks would render different scenes into one image.
  const std::uint64_t images = cli::scene_textures_hash(0, *loaded.scene);
  std::uint64_t rank0_images = images;
  MPI_Bcast(&rank0_images, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (int status = mpi::agree(world, mpi::attempt(program, [&] {
                                if (rank0_images != images)
                                  throw glint::Error("cannot render " + options.scene +
                                                     ": the images its spheres show differ "
                                                     "here from rank 0's");
                              })))
    return status;
  if (everywhere || (world.rank == 0 && (options.checkpoint || options.resume)))
    loaded.hash = cli::scene_textures_hash(loaded.hash, *loaded.scene);
  times.ready = mpi::seconds_since(start);
  return 0;
}

/// The variant that renders, chosen by rank 0 for every rank as glint-render chooses
/// (estimator_choice.hpp), or the status of a failure on any rank. `resumed`: rank 0's
/// --resume checkpoint, read here where it takes part in the choice.
std::variant<std::size_t, int> choose_variant(const mpi::World& world, const cli::Program& program,
                                              const cli::Options& options,
                                              const MpiOptions& mpi_options,
                                              const glint::Scene& scene,
                                              std::optional<glint::Checkpoint>& resumed) {
  std::uint64_t chosen = 0;
  if (int status = mpi::agree(world, mpi::attempt(program, [&] {
                                if (world.rank != 0) return;
                                if (!mpi_options.estimator)
                                  resumed = cli::PassKeeper::read_resumed(options);
                                chosen = mpi_options.estimator
                                             ? *mpi_options.estimator
                                             : cli::automatic_estimator(scene, resumed);
                              })))
    return status;
  MPI_Bcast(&chosen, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  return std::size_t(chosen);
}

/// Rank 0's render, once every rank's threads have started: the passes, then the outputs.
int render_on_rank0(const mpi::World& world, const cli::Program& program,
                    const cli::Options& options, const MpiOptions& mpi_options,
                    const std::string& output, const SceneOnRanks& loaded, cli::PassKeeper& keeper,
                    glint::PixelSums& sums, std::optional<mpi::RankRenderer>& renderer, int threads,
                    bool light_phase) {
  const glint::RenderSettings& settings = loaded.settings;
  // From here on, an error on rank 0 ends every rank (abort_run).
  try {
    const glint::RenderStart start = keeper.start();
    mpi::Coordinator coordinator(world, settings, sums, *renderer, threads, start.sums != nullptr,
                                 light_phase);
    const glint::RenderControl control{cli::ProgressPrinter(!options.quiet), keeper.callback(),
                                       &cli::stop_requested};
    glint::RenderResult result = coordinator.render(control, start.passes_done);
    renderer.reset();
    // The sums of the last completed pass (the render stops between passes), for the checkpoint.
    if (options.checkpoint) result.sums = std::move(sums);
    std::string lines = coordinator.report_lines(mpi_options.verbose);
    if (mpi_options.verbose)
      lines += mpi::load_line(world, loaded.times, mpi_options.scene_everywhere);
    return cli::finish_run(program, options, output, settings, std::move(result), keeper,
                           {coordinator.workers(), lines, world.size});
  } catch (const glint::ImageWriteError&) {
    // The render is over and every rank has ended its work: only rank 0 fails.
    const cli::Failure failure = cli::current_failure(program);
    std::cerr << failure.message;
    return failure.status;
  } catch (...) {
    mpi::abort_run(cli::current_failure(program).message);
  }
}

/// The render with variant V on every rank, its scene loaded: the threads started, then the
/// render, scheduled by rank 0.
template <typename V>
int render_with(const mpi::World& world, const cli::Program& program, const cli::Options& options,
                const MpiOptions& mpi_options, const std::string& output,
                const SceneOnRanks& loaded, std::optional<glint::Checkpoint> resumed) {
  const glint::RenderSettings& settings = loaded.settings;
  const glint::Scene& scene = *loaded.scene;
  if (int status = mpi::agree(world, mpi::attempt(program, [&] {
                                glint::check_supported<V>(scene);
                                mpi::check_same_image(
                                    program, options, settings,
                                    mpi_options.estimator
                                        ? cli::estimator_names()[*mpi_options.estimator]
                                        : std::string("auto"));
                              })))
    return status;
  const glint::TileGrid grid(settings);
  const int threads = int(std::min<std::size_t>(std::size_t(settings.threads), grid.count));

  std::optional<cli::PassKeeper> keeper;
  std::optional<glint::PixelSums> sums;
  std::optional<mpi::RankRenderer> renderer;
  const cli::ExecutionModel model = cli::execution_model(program, options);
  if (int status = mpi::agree(
          world, mpi::attempt(program, [&] {
            cli::with_memory_for(
                [&] {
                  return cli::image_memory(settings, options.resume.has_value(), cli::kSplats<V>);
                },
                [&] { sums.emplace(settings.width, settings.height, cli::kSplats<V>); });
            if (world.rank == 0) {
              keeper.emplace(program, options, settings, loaded.hash, std::move(resumed));
              if (const glint::RenderStart start = keeper->start(); start.sums) *sums = *start.sums;
            }
            renderer.emplace(program, [&](cli::TileQueue& queue) {
              return cli::with_renderer<V>(model, [&]<typename Renderer>() {
                return Renderer::render_tiles(scene, settings, *sums, queue);
              });
            });
            if (std::optional<cli::Failure> failure = renderer->started())
              throw glint::Error(failure->message);
          })))
    return status;

  if (world.rank != 0) {
    mpi::serve(world, settings, *renderer, *sums, threads);
    return 0;
  }
  constexpr bool kLightPhase =
      glint::kExecutionHasLightPhase<typename glint::Renderer<V>::ExecutionModel>;
  return render_on_rank0(world, program, options, mpi_options, output, loaded, *keeper, *sums,
                         renderer, threads, kLightPhase);
}

/// The run on every rank, its options read: the outputs checked, the scene loaded, the variant
/// chosen, then its render.
int render(const mpi::World& world, cli::Program& program, const cli::Options& options,
           const MpiOptions& mpi_options) {
  std::string output;
  if (int status = mpi::agree(world, mpi::attempt(program, [&] {
                                if (world.rank == 0) output = cli::check_outputs(options);
                              })))
    return status;
  SceneOnRanks loaded;
  if (int status = load_scene_on_ranks(world, program, options, mpi_options, loaded)) return status;
  std::optional<glint::Checkpoint> resumed;
  const std::variant<std::size_t, int> chosen =
      choose_variant(world, program, options, mpi_options, *loaded.scene, resumed);
  if (const int* status = std::get_if<int>(&chosen)) return *status;
  return cli::with_program_variant(std::get<std::size_t>(chosen), [&]<typename V>() {
    // What the messages, the summary, the checkpoint and the EXR header say is V's.
    program.variant = V::info.name;
    program.has_wavefront = cli::kHasWavefront<V>;
    program.wavefront_lanes = cli::kWavefrontLanes<V>;
    return render_with<V>(world, program, options, mpi_options, output, loaded, std::move(resumed));
  });
}

int run(const mpi::World& world, int argc, char** argv) {
  cli::Program program = kProgram;
  const std::string extra_options = cli::estimator_help() + std::string(kProgram.extra_options);
  program.extra_options = extra_options;
  program.chooses_variant = cli::kHoldsEstimators;
  cli::Options options;
  MpiOptions mpi_options;
  glint::Simd simd = glint::kCompiledSimd;
  if (const std::optional<int> status =
          read_command_line(world, argc, argv, program, options, mpi_options, simd))
    return *status;
  if (simd != glint::kCompiledSimd) return run_other_simd(world, program, simd, argc, argv);
  // Once MPI is initialised, so that these handlers, not MPI's, answer the stop signals; by the
  // instruction set that renders, whose stop flag they set.
  cli::install_signal_handlers(program.name, kStopSignals);
  return render(world, program, options, mpi_options);
}

}  // namespace

#if defined(GLINT_RENDER_SIMD_SETS)
extern "C" int GLINT_ISA_CONCAT(glint_render_mpi_, GLINT_ISA_LEVEL)(int rank, int size,
                                                                    const char* host, int argc,
                                                                    char** argv) {
  return run(mpi::World{rank, size, host, kProgram.name}, argc, argv);
}
#endif

#if !defined(GLINT_RENDER_SIMD_SETS) || defined(GLINT_RENDER_MAIN)
int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  mpi::World world;
  MPI_Comm_rank(MPI_COMM_WORLD, &world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world.size);
  char host[MPI_MAX_PROCESSOR_NAME];
  int host_size = 0;
  MPI_Get_processor_name(host, &host_size);
  world.host.assign(host, std::size_t(host_size));
  world.program = kProgram.name;
  const int status = run(world, argc, argv);
  MPI_Finalize();
  return status;
}
#endif
