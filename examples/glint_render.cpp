// glint-render: renders a scene file with one renderer variant, chosen when this file is
// compiled (GLINT_VARIANT names a type of glint::variants, e.g. -DGLINT_VARIANT=report). One
// executable per variant keeps each translation unit to a single instantiation of the renderer.

#include <cctype>
#include <charconv>
#include <cstdio>
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
Exit status: 0 on success, 1 for a bad scene or an unwritable output, 2 for bad options,
3 for a valid scene that this variant cannot render (a shading kind it was built without).
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
  return options;
}

void check_writable_directory(const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw glint::ImageWriteError("cannot write " + file + ": directory " + parent.string() +
                                 " does not exist");
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parse_options(argc, argv);
  } catch (const UsageError& error) {
    std::cerr << "glint-render: " << error.message << "\n\n" << kUsage;
    return 2;
  }
  try {
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(options.scene));
    glint::check_supported<Variant>(scene);

    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    if (options.spp) settings.samples_per_pixel = *options.spp;
    if (options.max_depth) settings.max_depth = *options.max_depth;
    if (options.width) settings.width = *options.width;
    if (options.height) settings.height = *options.height;
    if (options.threads) settings.threads = *options.threads;
    settings.seed = options.seed;

    const std::string output = options.output
                                   ? *options.output
                                   : std::filesystem::path(options.scene).stem().string() + ".png";
    check_writable_directory(output);
    if (options.hdr) check_writable_directory(*options.hdr);

    const glint::RenderResult result = glint::Renderer<Variant>::render(
        scene, settings, glint::cli::ProgressPrinter(!options.quiet));
    glint::write_png(result.film, output);
    if (options.hdr) glint::write_pfm(result.film, *options.hdr);

    if (!options.quiet) {
      const glint::RenderStats& stats = result.stats;
      std::fprintf(stderr,
                   "glint-render (%s): %s -> %s: %dx%d, %d spp, depth %d in %.2f s on %d threads: "
                   "%.3g samples, %.1f Mrays/s\n",
                   std::string(kVariantName).c_str(), options.scene.c_str(), output.c_str(),
                   settings.width, settings.height, settings.samples_per_pixel, settings.max_depth,
                   stats.seconds, stats.threads, double(stats.samples),
                   double(stats.rays) / stats.seconds * 1e-6);
    }
    if (result.stats.invalid_samples > 0)
      std::fprintf(stderr, "glint-render: warning: %llu samples were NaN or infinite and dropped\n",
                   static_cast<unsigned long long>(result.stats.invalid_samples));
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
