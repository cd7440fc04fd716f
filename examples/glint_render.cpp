// glint-render: renders a scene file with one renderer variant, chosen when this file is
// compiled (GLINT_VARIANT names a type of glint::variants, e.g. -DGLINT_VARIANT=report). One
// executable per variant keeps each translation unit to a single instantiation of the renderer.

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <charconv>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glint/glint.hpp"
#include "progress_printer.hpp"

#ifndef GLINT_VARIANT
#define GLINT_VARIANT default_variant
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
  --spp N             samples per pixel (overrides the scene's image spp)
  --max-depth N       most bounces after the camera ray; 0 = direct light only
  --width W           image width in pixels (overrides the scene)
  --height H          image height in pixels (overrides the scene)
  --threads N         worker threads (default: one per hardware thread); the image does
                      not depend on it
  --seed N            random seed (default 0): same scene, settings and seed give the
                      same image bit for bit
  --quiet             no progress or summary on stderr
  -h, --help          this help

Progress with an estimated time left goes to stderr while rendering, then one summary line.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM or SIGHUP stops after the current pass and writes the image of the
passes done, saying how many samples per pixel it holds; a second one exits at once.
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written.
Exit status: 0 on success, 1 for a bad scene or an unwritable output, 2 for bad options,
3 for a valid scene that this variant cannot render (a shading kind it was built without),
128 + the signal's number when a signal stopped the render (130 for SIGINT).
)";

struct Options {
  std::string scene;
  std::optional<std::string> output;
  std::optional<std::string> hdr;
  std::optional<int> spp, max_depth, width, height, threads;
  std::uint64_t seed = 0;
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

/// Output formats follow the file name, and only these two exist: a picture written under
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
std::atomic<int> stop_signal{0};  ///< the first stop signal received, or 0
constexpr int kMaxTemporaries = 2;
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

/// Writes every output to a new temporary file, then renames them all into place only when
/// all were written; on any failure, or a second signal, no temporary is left.
void write_outputs(const glint::Film& film, const std::string& png,
                   const std::optional<std::string>& pfm) {
  std::vector<glint::FileContents> files{{png, glint::encode_png(film)}};
  if (pfm) files.push_back({*pfm, glint::encode_pfm(film)});

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

    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(options.scene));
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

    const glint::RenderResult result = glint::Renderer<Variant>::render(
        scene, settings,
        glint::RenderControl{glint::cli::ProgressPrinter(!options.quiet), {}, &stop_requested});
    const int signal = stop_signal.load();
    if (result.samples_per_pixel == 0) {
      std::fprintf(stderr, "glint-render: stopped by %s before a pass completed: nothing written\n",
                   signal_name(signal));
      return 128 + signal;
    }
    write_outputs(result.film, output, options.hdr);

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
    if (signal != 0) {
      std::fprintf(stderr,
                   "glint-render: stopped by %s: %s holds %d of %d samples per pixel (%d of %d "
                   "passes)\n",
                   signal_name(signal), output.c_str(), result.samples_per_pixel,
                   settings.samples_per_pixel, result.passes_done, result.pass_count);
      return 128 + signal;
    }
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
