// command_line.hpp's definitions: the options' parsing and the usage text.

#include "command_line.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "glint/render/render_settings.hpp"
#include "glint/scene/image_settings.hpp"
#include "instruction_sets.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

namespace {

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
    R"(  --seed N            random seed (default 0): same scene, settings and seed give the
                      same image bit for bit
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
  --resume FILE       continue the render saved in FILE (same scene file, variant and
                      image options, seed included; either execution model): the image
                      is then exactly the one an uninterrupted render gives; a checkpoint
                      of another render is refused (status 1) before any rendering
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

constexpr std::string_view kOptionsLast =
    R"(  --stats-json FILE   also write the run's figures (time, rays, Mrays/s, samples, NaN count,
                      threads, instruction set, variant...) as JSON, FILE ending in .json,
                      with the images
  --quiet             no progress or summary on stderr
  --list-simd         print the instruction sets (--simd) this program holds and this CPU
                      runs, one a line, narrowest first, and exit
  -h, --help          this help
)";

std::string usage(const Program& program) {
  const std::string_view scalar_help =
      program.has_wavefront ? kScalarHelpWavefront : kScalarHelpScalarOnly;
  std::string text;
  for (const std::string_view part :
       {std::string_view("usage: "), program.launcher, std::string_view(program.name),
        std::string_view(" SCENE [options]\n\n"), program.description, std::string_view("\n\n"),
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
    } else if (arg == "--list-simd") {
      options.list_simd = true;
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
    } else if (arg == "--stats-json") {
      options.stats_json = image_path(arg, value(), "JSON", ".json");
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
  return usage(program) + "\nvariant: " + std::string(program.variant) +
         (program.chooses_variant ? " unless --estimator or the scene asks for another" : "") +
         "\nexecution model: " +
         (program.has_wavefront ? "wavefront (the default), or scalar with --scalar"
                                : "scalar (this variant's only one)") +
         "\ninstruction sets (--simd): " + simd_list(program.simds) +
         " (auto: " + std::string(glint::simd_name(run_simd(program, automatic))) +
         " on this CPU)\n";
}
}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
