// render_command.hpp's definitions: glint-render's and glint-render-mpi's options, outputs,
// stop signals, scene loading, checkpoints and end of a run, compiled once for every renderer
// executable (the glint-cli library). Nothing here may depend on the variant: what differs by
// variant comes in a Program.

#include "render_command.hpp"

#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/scene/scene_error.hpp"
#include "load_progress.hpp"

// GLINT_HAVE_EXR: the library links glint::exr (apps/CMakeLists.txt, when OpenEXR is found).
#ifdef GLINT_HAVE_EXR
#include "glint/exr/exr_image.hpp"
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

namespace {

std::string_view to_string(ExecutionModel model) {
  return model == ExecutionModel::wavefront ? "wavefront" : "scalar";
}

/// The variant and execution model, as the summary line and the EXR header name them:
/// "fast, wavefront", "report, scalar".
std::string renderer_name(const Program& program, ExecutionModel model) {
  return std::string(program.variant) + ", " + std::string(to_string(model));
}

/// What the summary line says of the code that rendered: "avx512, 16 paths at once", "avx2,
/// one path at a time".
std::string simd_description(const Program& program, const Options& options) {
  const bool wavefront = execution_model(program, options) == ExecutionModel::wavefront;
  const int lanes = wavefront ? program.wavefront_lanes : 1;
  return std::string(glint::simd_name(glint::kCompiledSimd)) + ", " +
         (lanes == 1 ? std::string("one path at a time")
                     : std::to_string(lanes) + " paths at once");
}

// --- The options --------------------------------------------------------------------------

constexpr std::string_view kOptionsBeforeThreads = R"(options:
  -o, --output FILE   8-bit sRGB PNG to write, FILE ending in .png (default: SCENE's name
                      with .png, in the current directory)
  --hdr FILE          also write linear radiance as a PFM (portable float map), FILE ending
                      in .pfm
  --tonemap OP        how the PNG shows radiance above 1: clip (default), reinhard or aces;
                      the PFM keeps the linear radiance
  --exposure EV       scale the radiance by 2^EV before tone mapping the PNG (default 0)
  --exr FILE          also write linear radiance as an OpenEXR image, 32-bit float RGB with
                      the render settings in its header, FILE ending in .exr (in a build
                      with OpenEXR, Debian's libopenexr-dev)
  --exr-half          write the EXR in 16-bit half floats: half the size, 11 significant
                      bits; radiance above 65504, the largest half, is written as 65504
  --spp N             samples per pixel (overrides the scene's image spp)
  --max-depth N       most bounces after the camera ray; 0 = direct light only
  --width W           image width in pixels (overrides the scene)
  --height H          image height in pixels (overrides the scene)
)";

constexpr std::string_view kOptionsAfterThreads =
    R"(  --seed N            random seed (default 0): same scene, settings, seed and execution
                      model give the same image bit for bit
  --simd SET          instruction set to render with: auto (default: the widest this CPU
                      has), avx512 (16 paths at once), avx2 (8) or scalar (one); the
                      same image bit for bit with each
  --checkpoint FILE   save what --resume needs to continue the render to FILE: after a
                      pass, every --checkpoint-interval seconds, and at the end (finished,
                      stopped by a signal or by --time-limit); an existing FILE is refused
                      (status 1) unless it is the one given to --resume
  --checkpoint-interval SECONDS
                      least time between two checkpoints while rendering (default 60;
                      0: after every pass)
  --resume FILE       continue the render saved in FILE (same scene file, variant,
                      execution model and image options, seed included): the image is
                      then exactly the one an uninterrupted render gives; a checkpoint of
                      another render is refused (status 1) before any rendering
  --time-limit SECONDS
                      stop after the pass that ends past SECONDS of rendering and write
                      the image of the passes done (status 0, saying what it holds)
)";

/// --scalar's lines: what it does depends on whether the variant has the wavefront renderer.
constexpr std::string_view kScalarHelpWavefront =
    R"(  --scalar            render with the scalar renderer (one path at a time) instead of
                      the wavefront renderer (batches of paths, stage by stage; the
                      default): the same image, bit for bit
)";
constexpr std::string_view kScalarHelpScalarOnly =
    R"(  --scalar            accepted, and changes nothing: this variant has the scalar
                      renderer only (the wavefront renderer is for the variants that
                      follow one lobe per bounce)
)";

constexpr std::string_view kOptionsLast = R"(  --quiet             no progress or summary on stderr
  -h, --help          this help
)";

std::string usage(const Program& program) {
  const std::string_view scalar_help =
      program.has_wavefront ? kScalarHelpWavefront : kScalarHelpScalarOnly;
  std::string text;
  for (const std::string_view part :
       {program.usage_line, std::string_view("\n\n"), program.description, std::string_view("\n\n"),
        kOptionsBeforeThreads, program.threads_help, scalar_help, kOptionsAfterThreads,
        program.extra_options, kOptionsLast, std::string_view("\n"), program.notes})
    text += part;
  return text;
}

template <typename Int>
Int parse_integer(std::string_view option, std::string_view text, Int low, Int high) {
  Int value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < low || value > high)
    throw UsageError{std::string(option) + " expects an integer in [" + std::to_string(low) + ", " +
                     std::to_string(high) + "], got '" + std::string(text) + "'"};
  return value;
}

/// A number of seconds: a decimal number from 0 to about 30 years.
double parse_seconds(std::string_view option, std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value >= 0.0) || value > 1e9)
    throw UsageError{std::string(option) + " expects seconds from 0 to 1e9, got '" +
                     std::string(text) + "'"};
  return value;
}

/// A number of stops: a decimal number within +-glint::limits::max_exposure.
float parse_exposure(std::string_view option, std::string_view text) {
  if (const std::optional<float> value = glint::parse_exposure(text)) return *value;
  throw UsageError{std::string(option) + " expects " + glint::exposure_range_text() + ", got '" +
                   std::string(text) + "'"};
}

glint::ToneMapOperator parse_tone_map(std::string_view option, std::string_view text) {
  if (const auto op = glint::parse_tone_map_operator(text)) return *op;
  throw UsageError{std::string(option) + " expects " + glint::tone_map_operator_list() + ", got '" +
                   std::string(text) + "'"};
}

/// --simd's value: an instruction set, or nullopt for auto.
std::optional<glint::Simd> parse_simd(std::string_view option, std::string_view text) {
  if (text == "auto") return std::nullopt;
  for (const glint::Simd simd : {glint::Simd::scalar, glint::Simd::avx2, glint::Simd::avx512})
    if (text == glint::simd_name(simd)) return simd;
  throw UsageError{std::string(option) + " expects auto, avx512, avx2 or scalar, got '" +
                   std::string(text) + "'"};
}

/// "scalar, avx2, avx512".
std::string simd_list(std::span<const glint::Simd> simds) {
  std::string list;
  for (const glint::Simd simd : simds)
    list += (list.empty() ? "" : ", ") + std::string(glint::simd_name(simd));
  return list;
}

/// Output formats follow the file name, and only these exist: a picture written under
/// another name (a PNG called out.jpg) would mislead every program that opens it.
std::string image_path(std::string_view option, std::string_view path, std::string_view format,
                       std::string_view extension) {
  const auto has_extension = [&] {
    if (path.size() <= extension.size()) return false;
    const std::string_view tail = path.substr(path.size() - extension.size());
    for (std::size_t i = 0; i < tail.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(tail[i])) != extension[i]) return false;
    return true;
  };
  if (!has_extension())
    throw UsageError{std::string(option) + " writes " + std::string(format) +
                     ": the file name must end in " + std::string(extension) + ", got '" +
                     std::string(path) + "'"};
  return std::string(path);
}

/// The number of single-character insertions, deletions and substitutions that turn `a` into
/// `b` (Levenshtein).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// " (did you mean '--spp'?)" for an unknown option within two edits, and a third of its
/// length, of one that `usage` lists, else "". The usage text is the one list of the options:
/// an option is a word starting with '-' that starts one of its lines, or follows ", " there.
std::string nearest_option_hint(std::string_view unknown, std::string_view usage) {
  std::string_view best;
  std::size_t best_distance = 3;
  std::size_t start = 0;
  while (start < usage.size()) {
    std::size_t end = usage.find('\n', start);
    if (end == std::string_view::npos) end = usage.size();
    std::string_view line = usage.substr(start, end - start);
    start = end + 1;
    // "  -o, --output FILE   ...": the option words before the first run of two spaces.
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string_view::npos || indent == 0 || line[indent] != '-') continue;
    line = line.substr(indent, line.find("  ", indent) - indent);
    while (!line.empty() && line[0] == '-') {
      const std::size_t word_end = line.find_first_of(" ,");
      const std::string_view option = line.substr(0, word_end);
      const std::size_t distance = edit_distance(unknown, option);
      // At most a third of the longer word changed: '-x' is not a misspelt '-o'.
      if (distance < best_distance && 3 * distance <= std::max(unknown.size(), option.size())) {
        best = option;
        best_distance = distance;
      }
      if (word_end == std::string_view::npos) break;
      line.remove_prefix(line.compare(word_end, 2, ", ") == 0 ? word_end + 2 : line.size());
    }
  }
  return best.empty() ? "" : " (did you mean '" + std::string(best) + "'?)";
}

}  // namespace

ExecutionModel execution_model(const Program& program, const Options& options) {
  return program.has_wavefront && !options.scalar ? ExecutionModel::wavefront
                                                  : ExecutionModel::scalar;
}

Options parse_options(int argc, char** argv, const Program& program, const ExtraOption& extra) {
  Options options;
  std::vector<std::string_view> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view arg = args[i];
    const std::function<std::string_view()> value = [&]() -> std::string_view {
      if (i + 1 >= args.size()) throw UsageError{std::string(arg) + " needs a value"};
      return args[++i];
    };
    if (arg == "-h" || arg == "--help") {
      options.help = true;
      return options;
    } else if (arg == "-o" || arg == "--output") {
      options.output = image_path(arg, value(), "an 8-bit sRGB PNG", ".png");
    } else if (arg == "--hdr") {
      options.hdr = image_path(arg, value(), "a linear float PFM", ".pfm");
    } else if (arg == "--tonemap") {
      options.tone_mapping.op = parse_tone_map(arg, value());
    } else if (arg == "--exposure") {
      options.tone_mapping.exposure = parse_exposure(arg, value());
    } else if (arg == "--exr") {
      options.exr = image_path(arg, value(), "an OpenEXR image", ".exr");
#ifndef GLINT_HAVE_EXR
      throw UsageError{"this " + std::string(program.name) +
                       " was built without OpenEXR (Debian: libopenexr-dev); "
                       "--exr is not available: install it (scripts/install-deps --exr) and "
                       "build glint again"};
#endif
    } else if (arg == "--exr-half") {
      options.exr_half = true;
    } else if (arg == "--spp") {
      options.spp = parse_integer(arg, value(), 1, glint::limits::max_samples_per_pixel);
    } else if (arg == "--max-depth") {
      options.max_depth = parse_integer(arg, value(), 0, glint::limits::max_depth);
    } else if (arg == "--width") {
      options.width = parse_integer(arg, value(), 1, glint::limits::max_image_side);
    } else if (arg == "--height") {
      options.height = parse_integer(arg, value(), 1, glint::limits::max_image_side);
    } else if (arg == "--threads") {
      options.threads = parse_integer(arg, value(), 1, glint::limits::max_threads);
    } else if (arg == "--seed") {
      options.seed = parse_integer<std::uint64_t>(arg, value(), 0, UINT64_MAX);
    } else if (arg == "--scalar") {
      options.scalar = true;
    } else if (arg == "--simd") {
      options.simd = parse_simd(arg, value());
    } else if (arg == "--checkpoint") {
      options.checkpoint = std::string(value());
    } else if (arg == "--checkpoint-interval") {
      options.checkpoint_interval = parse_seconds(arg, value());
    } else if (arg == "--resume") {
      options.resume = std::string(value());
    } else if (arg == "--time-limit") {
      options.time_limit = parse_seconds(arg, value());
    } else if (arg == "--quiet" || arg == "-q") {
      options.quiet = true;
    } else if (extra && extra(arg, value)) {
      continue;
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError{"unknown option '" + std::string(arg) + "'" +
                       nearest_option_hint(arg, usage(program))};
    } else if (options.scene.empty()) {
      options.scene = std::string(arg);
    } else {
      throw UsageError{"more than one scene given ('" + options.scene + "' and '" +
                       std::string(arg) + "')"};
    }
  }
  if (options.scene.empty()) throw UsageError{"no scene file given"};
  if (options.exr_half && !options.exr) throw UsageError{"--exr-half needs --exr FILE"};
  if (options.simd) run_simd(program, options);  // one the program holds and the CPU runs
  // Checked before the scene is read, which can take long: the scene cannot change this.
  if (options.width && options.height &&
      std::int64_t{*options.width} * *options.height > glint::limits::max_image_pixels)
    throw UsageError{"--width " + std::to_string(*options.width) + " --height " +
                     std::to_string(*options.height) + " exceeds " +
                     std::to_string(glint::limits::max_image_pixels) + " pixels"};
  return options;
}

std::string help_text(const Program& program) {
  Options automatic;
  return usage(program) + "\nvariant: " + std::string(program.variant) + "\nexecution model: " +
         (program.has_wavefront ? "wavefront (the default), or scalar with --scalar"
                                : "scalar (this variant's only one)") +
         "\ninstruction sets (--simd): " + simd_list(program.simds) +
         " (auto: " + std::string(glint::simd_name(run_simd(program, automatic))) +
         " on this CPU)\n";
}

bool cpu_runs(glint::Simd simd) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  switch (simd) {
    case glint::Simd::scalar:
      return true;
#if defined(__clang__)
    // clang 14 knows no psABI levels: the features that set x86-64-v3 and v4 apart that it can
    // test (the others, F16C, LZCNT and MOVBE, came with AVX2 in every such CPU).
    case glint::Simd::avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    case glint::Simd::avx512:
      return cpu_runs(glint::Simd::avx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
#else
    case glint::Simd::avx2:
      return __builtin_cpu_supports("x86-64-v3");
    case glint::Simd::avx512:
      return __builtin_cpu_supports("x86-64-v4");
#endif
  }
  return false;
#else
  return simd == glint::kCompiledSimd;
#endif
}

glint::Simd run_simd(const Program& program, const Options& options) {
  const auto built = [&](glint::Simd simd) {
    return std::find(program.simds.begin(), program.simds.end(), simd) != program.simds.end();
  };
  if (options.simd) {
    const std::string name(glint::simd_name(*options.simd));
    if (!built(*options.simd))
      throw UsageError{"--simd " + name + ": this program (variant " +
                       std::string(program.variant) + ") was compiled for " +
                       simd_list(program.simds) +
                       " only; glint-render, of the default variant, holds every instruction set"};
    if (!cpu_runs(*options.simd))
      throw UsageError{"--simd " + name + ": this CPU lacks the instruction set (" +
                       (*options.simd == glint::Simd::avx512 ? "x86-64-v4, AVX-512"
                                                             : "x86-64-v3, AVX2 and FMA") +
                       ")"};
    return *options.simd;
  }
  for (auto simd = program.simds.rbegin(); simd != program.simds.rend(); ++simd)
    if (cpu_runs(*simd)) return *simd;
  return program.simds.front();
}

// --- Stop signals -------------------------------------------------------------------------
// What the handler shares with the program: only lock-free atomics and fixed buffers, written
// with the signals blocked, so that the handler reads them whole.

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free &&
              std::atomic<std::int64_t>::is_always_lock_free);
std::atomic<bool> stop_requested{false};

namespace {

std::atomic<int> stop_signal{0};  ///< the first stop signal received, or 0
/// When the first stop signal came (CLOCK_MONOTONIC, nanoseconds); 0 until its handler has
/// noted it.
std::atomic<std::int64_t> first_stop_time{0};
/// The same signal again within this time of the first is the same stop, not a second one:
/// `timeout`, systemd and job schedulers signal the process and then its process group, so
/// the process gets two copies at once.
constexpr std::int64_t kRepeatedSignalWindow = 1'000'000'000;
constexpr int kMaxTemporaries = 4;  // the PNG, the PFM, the EXR and the checkpoint
char temporaries[kMaxTemporaries][PATH_MAX];
std::atomic<int> temporary_count{0};
constexpr int kMaxStopSignals = 4;
int stop_signals[kMaxStopSignals];
int stop_signal_count = 0;
char second_signal_message[128];
std::size_t second_signal_message_size = 0;

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    case SIGUSR1:
      return "SIGUSR1";
    default:
      return "a signal";
  }
}

/// Holds the stop signals back for its lifetime, so that a second signal's handler never sees
/// the list of temporaries half-updated or a set of outputs half-renamed.
class BlockStopSignals {
 public:
  BlockStopSignals() {
    sigset_t signals;
    sigemptyset(&signals);
    for (int i = 0; i < stop_signal_count; ++i)
      sigaddset(&signals, stop_signals[i]);
    pthread_sigmask(SIG_BLOCK, &signals, &previous_);
  }
  ~BlockStopSignals() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  BlockStopSignals(const BlockStopSignals&) = delete;
  BlockStopSignals& operator=(const BlockStopSignals&) = delete;

 private:
  sigset_t previous_;
};

/// Forgets the temporaries the handler would remove, when the files themselves are gone or
/// renamed (declared before them, it runs after their removal).
struct ForgetTemporaries {
  ~ForgetTemporaries() {
    const BlockStopSignals block;
    temporary_count.store(0);
  }
};

}  // namespace

// Internal linkage: glint-render links this file once per instruction set.
extern "C" {
static void on_stop_signal(int signal) {
  // Async-signal-safe only: atomics, clock_gettime, unlink, write and _exit.
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  const std::int64_t time = std::int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
  int first = 0;
  if (stop_signal.compare_exchange_strong(first, signal)) {
    first_stop_time.store(std::max<std::int64_t>(time, 1));
    stop_requested.store(true);
    return;
  }
  // The same signal while the first one's handler is still noting its time, or soon after it:
  // another copy of the same stop.
  const std::int64_t first_time = first_stop_time.load();
  if (first == signal && (first_time == 0 || time - first_time < kRepeatedSignalWindow)) return;
  for (int i = 0, n = temporary_count.load(); i < n; ++i)
    unlink(temporaries[i]);
  [[maybe_unused]] const ssize_t written =
      write(STDERR_FILENO, second_signal_message, second_signal_message_size);
  _exit(128 + signal);
}
}

void install_signal_handlers(const char* program, std::span<const int> signals) {
  std::snprintf(second_signal_message, sizeof second_signal_message,
                "\n%s: a second stop signal: exiting at once\n", program);
  second_signal_message_size = std::strlen(second_signal_message);
  stop_signal_count = 0;
  for (const int signal : signals.first(std::min<std::size_t>(signals.size(), kMaxStopSignals)))
    stop_signals[stop_signal_count++] = signal;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < stop_signal_count; ++i) {
    // A signal ignored on entry stays ignored: nohup and background jobs rely on it.
    struct sigaction previous {};
    if (sigaction(stop_signals[i], nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
      continue;
    sigaction(stop_signals[i], &action, nullptr);
  }
  // Past `ulimit -f`, write() then fails with EFBIG and the temporary is removed; by default
  // the signal would kill the process and leave the temporary behind.
  std::signal(SIGXFSZ, SIG_IGN);
}

// --- Outputs ------------------------------------------------------------------------------

namespace {

/// Refuses, before any rendering, an output that cannot be written or would destroy the scene.
void check_output(const std::string& output, const std::string& scene) {
  glint::check_output_path(output);
  std::error_code error;
  if (std::filesystem::equivalent(output, scene, error))
    throw glint::ImageWriteError("cannot write " + output + ": it is the scene file " + scene);
}

/// A file to write: its target and what writes its content into the temporary (write() or
/// append() then finish()).
struct StagedOutput {
  std::filesystem::path path;
  std::function<void(glint::StagedFile&)> write;
};

/// Writes every file to a new temporary file, then renames them all into place only when all
/// were written; on any failure, or a second signal, no temporary is left.
void write_staged(const std::vector<StagedOutput>& outputs) {
  const ForgetTemporaries forget;
  std::vector<glint::StagedFile> staged;
  staged.reserve(outputs.size());
  {
    const BlockStopSignals block;
    for (const StagedOutput& output : outputs) {
      staged.emplace_back(output.path);
      const std::string& name = staged.back().temporary().native();
      if (name.size() >= PATH_MAX)
        throw glint::ImageWriteError("cannot write " + output.path.string() + ": path too long");
      std::memcpy(temporaries[temporary_count.load()], name.c_str(), name.size() + 1);
      temporary_count.fetch_add(1);
    }
  }
  for (std::size_t i = 0; i < outputs.size(); ++i)
    outputs[i].write(staged[i]);
  const BlockStopSignals block;
  for (glint::StagedFile& file : staged)
    file.commit();
}

/// The checkpoint as a StagedOutput, encoded piece by piece into its temporary: never a copy of
/// the sums (24 bytes a pixel) in memory.
StagedOutput checkpoint_output(const std::string& path, const glint::CheckpointKey& key,
                               int passes_done, int samples_per_pixel_done,
                               const glint::PixelSums& sums) {
  return {path, [&key, passes_done, samples_per_pixel_done, &sums](glint::StagedFile& file) {
            glint::encode_checkpoint_pieces(
                key, passes_done, samples_per_pixel_done, sums,
                [&](const char* data, std::size_t size) { file.append(data, size); });
            file.finish();
          }};
}

}  // namespace

std::string check_outputs(const Options& options) {
  const std::string output = options.output
                                 ? *options.output
                                 : std::filesystem::path(options.scene).stem().string() + ".png";
  check_output(output, options.scene);
  if (options.hdr) check_output(*options.hdr, options.scene);
  if (options.exr) check_output(*options.exr, options.scene);
  if (options.checkpoint) {
    check_output(*options.checkpoint, options.scene);
    // The files are renamed into place together: one would silently replace the other.
    const auto resolved = [](const std::string& path) {
      return std::filesystem::weakly_canonical(std::filesystem::absolute(path));
    };
    for (const std::optional<std::string>& image :
         {std::optional(output), options.hdr, options.exr})
      if (image && resolved(*image) == resolved(*options.checkpoint))
        throw glint::ImageWriteError("cannot write the checkpoint " + *options.checkpoint +
                                     ": it is also the image " + *image);
    // A checkpoint is replaced only by the render it holds, continued: a run repeated without
    // --resume would replace the passes of hours with those of minutes.
    std::error_code error;
    const std::string& file = *options.checkpoint;
    if (std::filesystem::exists(std::filesystem::symlink_status(file, error)) &&
        !(options.resume && std::filesystem::equivalent(*options.resume, file, error)))
      throw glint::ImageWriteError("cannot write the checkpoint " + file +
                                   ": it exists, and may hold more of the render than this run "
                                   "will: continue it with --resume " +
                                   file + ", or remove it to start again");
  }
  // What a run killed while writing (kill -9 during a checkpoint) left beside the targets.
  for (const std::optional<std::string>& target :
       {std::optional(output), options.hdr, options.exr, options.checkpoint})
    if (target) glint::remove_stale_temporaries(*target);
  return output;
}

// --- The scene and the settings -----------------------------------------------------------

std::string scene_file_text(LoadProgress& loading, const std::string& file) {
  return glint::read_scene_file_text(file, loading.reader_callback());
}

std::uint64_t scene_text_hash(std::string_view text) {
  return glint::fnv1a(text.data(), text.size());
}

glint::Scene parse_and_build(LoadProgress& loading, std::string text, const std::string& source) {
  const glint::SceneDescription description =
      glint::read_scene_text(text, source, loading.reader_callback());
  std::string().swap(text);
  loading.building(description.spheres.size());
  glint::Scene built = glint::Scene::build(description);
  loading.finished(built.sphere_count());
  return built;
}

LoadedScene load_scene(const std::string& file, bool report, bool hash) {
  LoadProgress loading(report, file);
  std::string text = scene_file_text(loading, file);
  const std::uint64_t text_hash = hash ? scene_text_hash(text) : 0;
  return {parse_and_build(loading, std::move(text), file), text_hash};
}

glint::RenderSettings render_settings(const Options& options, const glint::Scene& scene) {
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  if (options.spp) settings.samples_per_pixel = *options.spp;
  if (options.max_depth) settings.max_depth = *options.max_depth;
  if (options.width) settings.width = *options.width;
  if (options.height) settings.height = *options.height;
  if (options.threads) settings.threads = *options.threads;
  settings.seed = options.seed;
  if (const std::string problem = glint::image_settings_problem(settings); !problem.empty())
    throw UsageError{"the options with " + options.scene + "'s image settings: " + problem};
  return settings;
}

// --- Checkpoints and the passes -----------------------------------------------------------

namespace {

/// The variant a checkpoint's key names: for the scalar renderer the variant's name alone, as
/// before there was a wavefront renderer, so that those checkpoints still resume (with --scalar,
/// bit for bit); for the wavefront renderer "NAME, wavefront", so that no checkpoint continues
/// in the other execution model, whose image differs in its last bits.
std::string checkpoint_variant(const Program& program, ExecutionModel model) {
  return model == ExecutionModel::scalar ? std::string(program.variant)
                                         : renderer_name(program, model);
}

/// Refuses a checkpoint of this variant's other execution model, saying so and how to resume
/// it (check_checkpoint_matches would only show two variant names).
void check_execution_model(const glint::Checkpoint& checkpoint, const Program& program,
                           ExecutionModel model, const std::string& file) {
  const ExecutionModel other =
      model == ExecutionModel::scalar ? ExecutionModel::wavefront : ExecutionModel::scalar;
  if (checkpoint.key.variant != checkpoint_variant(program, other)) return;
  throw glint::CheckpointError(
      "cannot resume from " + file + ": it was made by the " + std::string(to_string(other)) +
      " renderer, this render is " + std::string(to_string(model)) +
      " (their images differ in the last bits): resume it " +
      (other == ExecutionModel::scalar ? "with" : "without") + " --scalar");
}

}  // namespace

PassKeeper::PassKeeper(const Program& program, const Options& options,
                       const glint::RenderSettings& settings, std::uint64_t scene_hash)
    : program_(program), options_(options) {
  const ExecutionModel model = execution_model(program, options);
  if (options.checkpoint || options.resume)
    key_ = glint::CheckpointKey::of(scene_hash, checkpoint_variant(program, model), settings);
  if (options.resume) {
    resumed_ = glint::read_checkpoint(*options.resume);
    check_execution_model(*resumed_, program, model, *options.resume);
    glint::check_checkpoint_matches(*resumed_, key_, *options.resume);
    last_passes_ = resumed_->passes_done;
    last_spp_ = resumed_->samples_per_pixel_done;
  }
}

glint::RenderStart PassKeeper::start() const {
  return resumed_ ? glint::RenderStart{&resumed_->sums, resumed_->passes_done}
                  : glint::RenderStart{};
}

bool PassKeeper::pass_done(const glint::PassReport& pass) {
  last_passes_ = pass.passes_done;
  last_spp_ = pass.samples_per_pixel;
  const bool last = pass.passes_done == pass.pass_count;
  if (options_.time_limit && pass.elapsed_seconds >= *options_.time_limit && !last) {
    time_is_up_ = true;
    return false;
  }
  // The last pass's checkpoint is written with the images.
  if (options_.checkpoint && !last &&
      pass.elapsed_seconds - last_checkpoint_ >= options_.checkpoint_interval) {
    try {
      write_staged({checkpoint_output(*options_.checkpoint, key_, pass.passes_done,
                                      pass.samples_per_pixel, pass.sums)});
    } catch (const glint::ImageWriteError& error) {
      // Hours of rendering are worth more than one checkpoint: the next one may succeed.
      std::fprintf(stderr, "\n%s: warning: no checkpoint: %s\n", program_.name, error.what());
    }
    last_checkpoint_ = pass.elapsed_seconds;
  }
  return true;
}

glint::PassCallback PassKeeper::callback() {
  return [this](const glint::PassReport& pass) { return pass_done(pass); };
}

void PassKeeper::write_final_checkpoint(const glint::PixelSums& sums) const {
  write_staged({checkpoint_output(*options_.checkpoint, key_, last_passes_, last_spp_, sums)});
}

// --- The end of a run ---------------------------------------------------------------------

#ifdef GLINT_HAVE_EXR
namespace {

/// The render, in the EXR header: a typed attribute per setting ("glint/..."; the seed as its
/// decimal string, EXR having no 64-bit integers), and a line in the standard "comments"
/// attribute that any EXR viewer shows. The scene is named as it was given.
std::vector<glint::ExrAttribute> exr_attributes(const Program& program, const Options& options,
                                                const glint::RenderSettings& settings,
                                                const glint::RenderResult& result) {
  const std::string seed = std::to_string(settings.seed);
  const ExecutionModel model = execution_model(program, options);
  const std::string comments =
      std::string(program.name) + " " GLINT_VERSION " (" + renderer_name(program, model) +
      "): " + options.scene + ", " + std::to_string(result.samples_per_pixel) + " of " +
      std::to_string(settings.samples_per_pixel) + " samples per pixel, max depth " +
      std::to_string(settings.max_depth) + ", seed " + seed;
  return {{"comments", comments},
          {"glint/version", std::string(GLINT_VERSION)},
          {"glint/variant", std::string(program.variant)},
          {"glint/executionModel", std::string(to_string(model))},
          {"glint/simd", std::string(glint::simd_name(glint::kCompiledSimd))},
          {"glint/scene", options.scene},
          {"glint/width", settings.width},
          {"glint/height", settings.height},
          {"glint/samplesPerPixel", result.samples_per_pixel},
          {"glint/samplesPerPixelRequested", settings.samples_per_pixel},
          {"glint/maxDepth", settings.max_depth},
          {"glint/antialiasSigma", settings.antialias_sigma},
          {"glint/seed", seed},
          {"glint/threads", result.stats.threads},
          {"glint/renderSeconds", result.stats.seconds}};
}

}  // namespace
#endif

int finish_run(const Program& program, const Options& options, const std::string& output,
               const glint::RenderSettings& settings, glint::RenderResult result,
               const PassKeeper& keeper, const RunReport& report) {
  const char* name = program.name;
  const int signal = stop_signal.load();
  if (result.samples_per_pixel == 0) {
    std::fprintf(stderr, "%s: stopped by %s before a pass completed: nothing written\n", name,
                 signal_name(signal));
    return 128 + signal;
  }
  // The checkpoint first, so that its sums (24 bytes a pixel) are freed before the images are
  // encoded. It is a means to the images, which are written whatever becomes of it: its
  // failure is reported last, and makes the status 1.
  std::string checkpoint_failure;
  if (options.checkpoint) {
    try {
      keeper.write_final_checkpoint(result.sums);
    } catch (const glint::ImageWriteError& error) {
      checkpoint_failure = error.what();
    }
    result.sums = glint::PixelSums();
  }

  std::vector<glint::FileContents> files{
      {output, glint::encode_png(result.film, options.tone_mapping)}};
  if (options.hdr) files.push_back({*options.hdr, glint::encode_pfm(result.film)});
#ifdef GLINT_HAVE_EXR
  std::size_t clamped_halves = 0;
  if (options.exr) {
    glint::ExrEncoded exr = glint::encode_exr(
        result.film,
        {options.exr_half ? glint::ExrPixelType::float16 : glint::ExrPixelType::float32,
         exr_attributes(program, options, settings, result)});
    clamped_halves = exr.clamped_values;
    files.push_back({*options.exr, std::move(exr.bytes)});
  }
#endif
  std::vector<StagedOutput> images;
  for (const glint::FileContents& file : files)
    images.push_back({file.path, [&file](glint::StagedFile& staged) { staged.write(file.bytes); }});
  write_staged(images);

  if (!options.quiet) {
    const glint::RenderStats& stats = result.stats;
    std::fprintf(stderr,
                 "%s (%s): %s -> %s: %dx%d, %d spp, depth %d in %.2f s on %s: "
                 "%.3g samples, %.1f Mrays/s\n",
                 name,
                 (renderer_name(program, execution_model(program, options)) + ", " +
                  simd_description(program, options))
                     .c_str(),
                 options.scene.c_str(), output.c_str(), settings.width, settings.height,
                 result.samples_per_pixel, settings.max_depth, stats.seconds,
                 report.workers.c_str(), double(stats.samples),
                 double(stats.rays) / stats.seconds * 1e-6);
    std::fputs(report.after_summary.c_str(), stderr);
  }
  if (result.stats.invalid_samples > 0)
    std::fprintf(stderr, "%s: warning: %llu samples were NaN or infinite and dropped\n", name,
                 static_cast<unsigned long long>(result.stats.invalid_samples));
  if (result.stats.clamped_pixels > 0)
    std::fprintf(stderr,
                 "%s: warning: %llu pixels have a mean beyond the float range and were "
                 "written as the largest float (%g)\n",
                 name, static_cast<unsigned long long>(result.stats.clamped_pixels),
                 double(std::numeric_limits<float>::max()));
#ifdef GLINT_HAVE_EXR
  if (clamped_halves > 0)
    std::fprintf(stderr,
                 "%s: warning: %zu channel values beyond the largest half were "
                 "written to %s as %g\n",
                 name, clamped_halves, options.exr->c_str(), double(glint::kExrLargestHalf));
#endif
  if (options.checkpoint && !result.complete() && checkpoint_failure.empty())
    std::fprintf(stderr, "%s: %s holds the render so far: continue it with --resume %s\n", name,
                 options.checkpoint->c_str(), options.checkpoint->c_str());
  if (signal != 0)
    std::fprintf(stderr,
                 "%s: stopped by %s: %s holds %d of %d samples per pixel (%d of %d "
                 "passes)\n",
                 name, signal_name(signal), output.c_str(), result.samples_per_pixel,
                 settings.samples_per_pixel, result.passes_done, result.pass_count);
  else if (keeper.time_is_up())
    std::fprintf(stderr,
                 "%s: time limit of %g s reached: %s holds %d of %d samples per pixel "
                 "(%d of %d passes)\n",
                 name, *options.time_limit, output.c_str(), result.samples_per_pixel,
                 settings.samples_per_pixel, result.passes_done, result.pass_count);
  if (!checkpoint_failure.empty()) {
    std::fprintf(stderr, "%s: error: no checkpoint: %s (the images were written)\n", name,
                 checkpoint_failure.c_str());
    return 1;
  }
  return signal != 0 ? 128 + signal : 0;
}

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
  } catch (const std::exception& error) {
    return {1, std::string(program.name) + ": error: " + error.what() + "\n"};
  } catch (...) {
    return {1, std::string(program.name) + ": error: an unknown exception\n"};
  }
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
