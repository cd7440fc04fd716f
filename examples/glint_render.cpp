// glint-render: renders a scene file with one renderer variant, chosen when this file is
// compiled (GLINT_VARIANT names a type of glint::variants, e.g. -DGLINT_VARIANT=report). One
// executable per variant keeps each translation unit to a single instantiation of the renderer.

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glint/glint.hpp"
#include "glint/io/checkpoint.hpp"
#include "load_progress.hpp"
#include "progress_printer.hpp"

#ifndef GLINT_VARIANT
#define GLINT_VARIANT default_variant
#endif
// GLINT_HAVE_EXR: this program links glint::exr (examples/CMakeLists.txt, when OpenEXR is found).
#ifdef GLINT_HAVE_EXR
#include "glint/exr/exr_image.hpp"
#endif

namespace {

using Variant = glint::variants::GLINT_VARIANT;
static_assert(glint::NamedVariant<Variant>, "GLINT_VARIANT must name a variant of variants.hpp");
constexpr std::string_view kVariantName = Variant::info.name;

constexpr std::string_view kUsage = R"(usage: glint-render SCENE [options]

Renders SCENE (a glint scene file) with the path tracer and writes an image.

options:
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
  --threads N         worker threads (default: one per hardware thread); the image does
                      not depend on it
  --seed N            random seed (default 0): same scene, settings and seed give the
                      same image bit for bit
  --checkpoint FILE   save what --resume needs to continue the render to FILE: after a
                      pass, every --checkpoint-interval seconds, and at the end (finished,
                      stopped by a signal or by --time-limit)
  --checkpoint-interval SECONDS
                      least time between two checkpoints while rendering (default 60;
                      0: after every pass)
  --resume FILE       continue the render saved in FILE (same scene file, variant and
                      image options, seed included): the image is then exactly the one
                      an uninterrupted render gives; a checkpoint of another render is
                      refused (status 1) before any rendering
  --time-limit SECONDS
                      stop after the pass that ends past SECONDS of rendering and write
                      the image of the passes done (status 0, saying what it holds)
  --quiet             no progress or summary on stderr
  -h, --help          this help

Progress with an estimated time left goes to stderr while rendering, then one summary line.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM or SIGHUP stops after the current pass and writes the image of the
passes done, saying how many samples per pixel it holds; a second one exits at once.
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written.
Exit status: 0 on success (--time-limit included), 1 for a bad scene, an unwritable output or
a checkpoint that cannot be resumed, 2 for bad options,
3 for a valid scene that this variant cannot render (a shading kind it was built without),
128 + the signal's number when a signal stopped the render (130 for SIGINT).
)";

struct Options {
  std::string scene;
  std::optional<std::string> output;
  std::optional<std::string> hdr;
  glint::ToneMapping tone_mapping;
  std::optional<std::string> exr;
  bool exr_half = false;
  std::optional<int> spp, max_depth, width, height, threads;
  std::uint64_t seed = 0;
  std::optional<std::string> checkpoint, resume;
  double checkpoint_interval = 60.0;
  std::optional<double> time_limit;
  bool quiet = false;
};

struct UsageError {
  std::string message;
};

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
  float value = 0.0f;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() ||
      !(std::abs(value) <= glint::limits::max_exposure))
    throw UsageError{std::string(option) + " expects stops from -" +
                     std::to_string(int(glint::limits::max_exposure)) + " to " +
                     std::to_string(int(glint::limits::max_exposure)) + ", got '" +
                     std::string(text) + "'"};
  return value;
}

glint::ToneMapOperator parse_tone_map(std::string_view option, std::string_view text) {
  if (const auto op = glint::parse_tone_map_operator(text)) return *op;
  throw UsageError{std::string(option) + " expects " + glint::tone_map_operator_list() +
                   ", got '" + std::string(text) + "'"};
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

Options parse_options(int argc, char** argv) {
  Options options;
  std::vector<std::string_view> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view arg = args[i];
    const auto value = [&]() -> std::string_view {
      if (i + 1 >= args.size()) throw UsageError{std::string(arg) + " needs a value"};
      return args[++i];
    };
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage << "\nvariant: " << kVariantName << "\n";
      std::exit(0);
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
      throw UsageError{
          "this glint-render was built without OpenEXR (Debian: libopenexr-dev); "
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
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError{"unknown option '" + std::string(arg) + "'"};
    } else if (options.scene.empty()) {
      options.scene = std::string(arg);
    } else {
      throw UsageError{"more than one scene given ('" + options.scene + "' and '" +
                       std::string(arg) + "')"};
    }
  }
  if (options.scene.empty()) throw UsageError{"no scene file given"};
  if (options.exr_half && !options.exr) throw UsageError{"--exr-half needs --exr FILE"};
  // Checked before the scene is read, which can take long: the scene cannot change this.
  if (options.width && options.height &&
      std::int64_t{*options.width} * *options.height > glint::limits::max_image_pixels)
    throw UsageError{"--width " + std::to_string(*options.width) + " --height " +
                     std::to_string(*options.height) + " exceeds " +
                     std::to_string(glint::limits::max_image_pixels) + " pixels"};
  return options;
}

/// The three signals that ask a render to stop. The first one stops after the current pass and
/// writes the image of the passes done; a second one exits at once.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

// What the signal handler shares with the program: only lock-free atomics and fixed buffers,
// written with the signals blocked, so that the handler reads them whole.
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);
std::atomic<bool> stop_requested{false};
std::atomic<int> stop_signal{0};    ///< the first stop signal received, or 0
constexpr int kMaxTemporaries = 4;  // the PNG, the PFM, the EXR and the checkpoint
char temporaries[kMaxTemporaries][PATH_MAX];
std::atomic<int> temporary_count{0};

extern "C" void on_stop_signal(int signal) {
  // Async-signal-safe only: atomics, unlink and _exit.
  if (stop_signal.exchange(signal) != 0) {
    for (int i = 0, n = temporary_count.load(); i < n; ++i)
      unlink(temporaries[i]);
    static constexpr char kMessage[] = "\nglint-render: a second stop signal: exiting at once\n";
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    _exit(128 + signal);
  }
  stop_requested.store(true);
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (const int signal : kStopSignals) {
    // A signal ignored on entry stays ignored: nohup and background jobs rely on it.
    struct sigaction previous {};
    if (sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(signal, &action, nullptr);
  }
  // Past `ulimit -f`, write() then fails with EFBIG and the temporary is removed; by default
  // the signal would kill the process and leave the temporary behind.
  std::signal(SIGXFSZ, SIG_IGN);
}

/// Holds the stop signals back for its lifetime, so that a second signal's handler never sees
/// the list of temporaries half-updated or a set of outputs half-renamed.
class BlockStopSignals {
 public:
  BlockStopSignals() {
    sigset_t signals;
    sigemptyset(&signals);
    for (const int signal : kStopSignals)
      sigaddset(&signals, signal);
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

/// Refuses, before any rendering, an output that cannot be written or would destroy the scene.
void check_output(const std::string& output, const std::string& scene) {
  glint::check_output_path(output);
  std::error_code error;
  if (std::filesystem::equivalent(output, scene, error))
    throw glint::ImageWriteError("cannot write " + output + ": it is the scene file " + scene);
}

/// Writes every file to a new temporary file, then renames them all into place only when all
/// were written; on any failure, or a second signal, no temporary is left.
void write_staged(const std::vector<glint::FileContents>& files) {
  const ForgetTemporaries forget;
  std::vector<glint::StagedFile> staged;
  staged.reserve(files.size());
  {
    const BlockStopSignals block;
    for (const glint::FileContents& file : files) {
      staged.emplace_back(file.path);
      const std::string& name = staged.back().temporary().native();
      if (name.size() >= PATH_MAX)
        throw glint::ImageWriteError("cannot write " + file.path.string() + ": path too long");
      std::memcpy(temporaries[temporary_count.load()], name.c_str(), name.size() + 1);
      temporary_count.fetch_add(1);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i)
    staged[i].write(files[i].bytes);
  const BlockStopSignals block;
  for (glint::StagedFile& file : staged)
    file.commit();
}

/// The hash of the scene file's bytes that a checkpoint records: the scene as written, so that
/// any edit, even one that renders the same, makes a checkpoint another scene's.
std::uint64_t scene_file_hash(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw glint::Error("cannot read " + path + ": " + std::strerror(errno));
  std::uint64_t hash = glint::fnv1a(nullptr, 0);
  std::vector<char> buffer(1 << 16);
  for (std::size_t read; (read = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0;)
    hash = glint::fnv1a(buffer.data(), read, hash);
  if (std::ferror(file.get())) throw glint::Error("cannot read " + path);
  return hash;
}

#ifdef GLINT_HAVE_EXR
/// The render, in the EXR header: a typed attribute per setting ("glint/..."; the seed as its
/// decimal string, EXR having no 64-bit integers), and a line in the standard "comments"
/// attribute that any EXR viewer shows. The scene is named as it was given.
std::vector<glint::ExrAttribute> exr_attributes(const Options& options,
                                                const glint::RenderSettings& settings,
                                                const glint::RenderResult& result) {
  const std::string seed = std::to_string(settings.seed);
  const std::string comments =
      "glint-render " GLINT_VERSION " (" + std::string(kVariantName) + "): " + options.scene +
      ", " + std::to_string(result.samples_per_pixel) + " of " +
      std::to_string(settings.samples_per_pixel) + " samples per pixel, max depth " +
      std::to_string(settings.max_depth) + ", seed " + seed;
  return {{"comments", comments},
          {"glint/version", std::string(GLINT_VERSION)},
          {"glint/variant", std::string(kVariantName)},
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
#endif

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "glint-render: " << message << "\n\n" << kUsage;
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parse_options(argc, argv);
  } catch (const UsageError& error) {
    usage_error(error.message);
  }
  install_signal_handlers();
  try {
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
    }

    const glint::Scene scene = [&] {
      glint::cli::LoadProgress loading(!options.quiet, options.scene);
      const glint::SceneDescription description =
          glint::read_scene_file(options.scene, loading.reader_callback());
      loading.building(description.spheres.size());
      glint::Scene built = glint::Scene::build(description);
      loading.finished(built.sphere_count());
      return built;
    }();
    glint::check_supported<Variant>(scene);

    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    if (options.spp) settings.samples_per_pixel = *options.spp;
    if (options.max_depth) settings.max_depth = *options.max_depth;
    if (options.width) settings.width = *options.width;
    if (options.height) settings.height = *options.height;
    if (options.threads) settings.threads = *options.threads;
    settings.seed = options.seed;
    // The scene's own settings were checked when it was read: what fails now is an option.
    if (const std::string problem = glint::image_settings_problem(settings); !problem.empty())
      usage_error("the options with " + options.scene + "'s image settings: " + problem);

    glint::CheckpointKey key;
    if (options.checkpoint || options.resume)
      key = glint::CheckpointKey::of(scene_file_hash(options.scene), kVariantName, settings);
    std::optional<glint::Checkpoint> resumed;
    if (options.resume) {
      resumed = glint::read_checkpoint(*options.resume);
      glint::check_checkpoint_matches(*resumed, key, *options.resume);
    }

    glint::RenderControl control{glint::cli::ProgressPrinter(!options.quiet), {}, &stop_requested};
    glint::RenderStart start;
    // The state of the last completed pass, for the checkpoint at the end: kept by the pass
    // callback, which sees every pass, whatever stops the render after it.
    glint::PixelSums last_sums;
    int last_passes = 0, last_spp = 0;
    if (resumed) {
      start = {&resumed->sums, resumed->passes_done};
      last_sums = resumed->sums;
      last_passes = resumed->passes_done;
      last_spp = resumed->samples_per_pixel_done;
    }
    bool time_is_up = false;
    double last_checkpoint = 0.0;
    control.pass_done = [&](const glint::PassReport& pass) {
      if (options.checkpoint) {
        last_sums = pass.sums;
        last_passes = pass.passes_done;
        last_spp = pass.samples_per_pixel;
      }
      const bool last = pass.passes_done == pass.pass_count;
      if (options.time_limit && pass.elapsed_seconds >= *options.time_limit && !last) {
        time_is_up = true;
        return false;
      }
      // The last pass's checkpoint is written with the images.
      if (options.checkpoint && !last &&
          pass.elapsed_seconds - last_checkpoint >= options.checkpoint_interval) {
        try {
          write_staged(
              {{*options.checkpoint, glint::encode_checkpoint(key, pass.passes_done,
                                                              pass.samples_per_pixel, pass.sums)}});
        } catch (const glint::ImageWriteError& error) {
          // Hours of rendering are worth more than one checkpoint: the next one may succeed.
          std::fprintf(stderr, "\nglint-render: warning: no checkpoint: %s\n", error.what());
        }
        last_checkpoint = pass.elapsed_seconds;
      }
      return true;
    };
    const glint::RenderResult result =
        glint::Renderer<Variant>::render(scene, settings, control, start);
    const int signal = stop_signal.load();
    if (result.samples_per_pixel == 0) {
      std::fprintf(stderr, "glint-render: stopped by %s before a pass completed: nothing written\n",
                   signal_name(signal));
      return 128 + signal;
    }
    std::vector<glint::FileContents> files{{output, glint::encode_png(result.film, options.tone_mapping)}};
    if (options.hdr) files.push_back({*options.hdr, glint::encode_pfm(result.film)});
#ifdef GLINT_HAVE_EXR
    std::size_t clamped_halves = 0;
    if (options.exr) {
      glint::ExrEncoded exr = glint::encode_exr(
          result.film,
          {options.exr_half ? glint::ExrPixelType::float16 : glint::ExrPixelType::float32,
           exr_attributes(options, settings, result)});
      clamped_halves = exr.clamped_values;
      files.push_back({*options.exr, std::move(exr.bytes)});
    }
#endif
    if (options.checkpoint)
      files.push_back(
          {*options.checkpoint, glint::encode_checkpoint(key, last_passes, last_spp, last_sums)});
    write_staged(files);

    if (!options.quiet) {
      const glint::RenderStats& stats = result.stats;
      std::fprintf(stderr,
                   "glint-render (%s): %s -> %s: %dx%d, %d spp, depth %d in %.2f s on %d threads: "
                   "%.3g samples, %.1f Mrays/s\n",
                   std::string(kVariantName).c_str(), options.scene.c_str(), output.c_str(),
                   settings.width, settings.height, result.samples_per_pixel, settings.max_depth,
                   stats.seconds, stats.threads, double(stats.samples),
                   double(stats.rays) / stats.seconds * 1e-6);
    }
    if (result.stats.invalid_samples > 0)
      std::fprintf(stderr, "glint-render: warning: %llu samples were NaN or infinite and dropped\n",
                   static_cast<unsigned long long>(result.stats.invalid_samples));
    if (result.stats.clamped_pixels > 0)
      std::fprintf(stderr,
                   "glint-render: warning: %llu pixels have a mean beyond the float range and were "
                   "written as the largest float (%g)\n",
                   static_cast<unsigned long long>(result.stats.clamped_pixels),
                   double(std::numeric_limits<float>::max()));
#ifdef GLINT_HAVE_EXR
    if (clamped_halves > 0)
      std::fprintf(stderr,
                   "glint-render: warning: %zu channel values beyond the largest half were "
                   "written to %s as %g\n",
                   clamped_halves, options.exr->c_str(), double(glint::kExrLargestHalf));
#endif
    if (options.checkpoint && !result.complete())
      std::fprintf(stderr,
                   "glint-render: %s holds the render so far: continue it with --resume %s\n",
                   options.checkpoint->c_str(), options.checkpoint->c_str());
    if (signal != 0) {
      std::fprintf(stderr,
                   "glint-render: stopped by %s: %s holds %d of %d samples per pixel (%d of %d "
                   "passes)\n",
                   signal_name(signal), output.c_str(), result.samples_per_pixel,
                   settings.samples_per_pixel, result.passes_done, result.pass_count);
      return 128 + signal;
    }
    if (time_is_up)
      std::fprintf(stderr,
                   "glint-render: time limit of %g s reached: %s holds %d of %d samples per pixel "
                   "(%d of %d passes)\n",
                   *options.time_limit, output.c_str(), result.samples_per_pixel,
                   settings.samples_per_pixel, result.passes_done, result.pass_count);
    return 0;
  } catch (const glint::UnsupportedSceneError& error) {
    std::cerr << error.what() << "\n";
    return 3;
  } catch (const glint::SceneError& error) {
    std::cerr << error.what() << "\n";  // already "FILE:LINE: error: PROBLEM"
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "glint-render: error: " << error.what() << "\n";
    return 1;
  }
}
