// glint-compare: a static HTML page comparing renders of the same scenes with a reference
// (an ablation viewer): per scene, every variant's image and its error map, flipped with keys
// or the mouse, zoomed to single pixels, with each variant's CPU time and RMSE. bench/run-all
// writes one for its renders at equal time; tests/viewer/viewer_test.bash opens one in Chromium.
//
//   glint-compare MANIFEST -o DIR [--tonemap OP] [--exposure EV] [--baseline VARIANT]
//                 [--title TEXT] [--note TEXT]
//
// The manifest is a tab-separated text file (of at most 16 MiB, lines of at most 65536
// characters); empty lines and lines starting with '#' are skipped, and relative paths are
// relative to the manifest's directory:
//
//   reference<TAB>SCENE<TAB>IMAGE[<TAB>DESCRIPTION]
//   variant<TAB>SCENE<TAB>VARIANT<TAB>IMAGE<TAB>CPU_SECONDS<TAB>SPP[<TAB>DESCRIPTION]
//
// An IMAGE is linear radiance: a PFM file, or an OpenEXR file (name ending in .exr) in a build
// with OpenEXR (GLINT_HAVE_EXR: glint::exr is linked).
//
// Every scene needs one reference, of the same size as its variants' images. Scenes and
// variants keep the manifest's order. DIR gets index.html (self-contained: styles, code and
// data inline, nothing fetched from a network) and, per scene, SCENE/reference.png,
// SCENE/variant-VARIANT.png and SCENE/error-VARIANT.png. Everything is read and checked before
// anything is written, and every file is staged and renamed into place only once all of them
// were written (glint::write_files), index.html last: a failure replaces none of the files
// (it may leave new, empty scene directories).
//
// Exit status: 0 written, 1 a manifest, image or output error (named with its file and line),
// 2 bad command line.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "compare_page_html.hpp"  // generated from compare_page.html (embed_page.cmake)
#include "glint/detail/text.hpp"
#include "glint/image/compare.hpp"
#include "glint/image/false_color.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/input_file.hpp"
#ifdef GLINT_HAVE_EXR
#include "glint/exr/exr_image.hpp"
#endif

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kUsage = R"(usage: glint-compare MANIFEST -o DIR [options]

Writes DIR/index.html, a page comparing each variant's render of a scene with the scene's
reference (images, error maps, CPU time and RMSE), and the PNG images it shows beside it.

MANIFEST is tab-separated, one image a line ('#' starts a comment line; relative paths are
relative to MANIFEST's directory):
  reference<TAB>SCENE<TAB>IMAGE[<TAB>DESCRIPTION]
  variant<TAB>SCENE<TAB>VARIANT<TAB>IMAGE<TAB>CPU_SECONDS<TAB>SPP[<TAB>DESCRIPTION]

options:
  -o, --output DIR    where the page and its images go (made if missing)
  --tonemap OP        how the PNGs show radiance: clip, reinhard (default) or aces
  --exposure EV       scale the radiance by 2^EV before tone mapping (default 0)
  --baseline VARIANT  the variant the ratios are to (default: each scene's first variant)
  --title TEXT        the page's title
  --note TEXT         a line under the title (how the images were made)
  -h, --help          this help
)";
#ifdef GLINT_HAVE_EXR
constexpr std::string_view kImageKinds =
    "\nIMAGE: a PFM or OpenEXR (.exr) file of linear radiance.\n";
#else
constexpr std::string_view kImageKinds =
    "\nIMAGE: a PFM file of linear radiance (this build has no OpenEXR, so no .exr).\n";
#endif

void print_usage(std::FILE* to) {
  std::fputs(kUsage.data(), to);
  std::fputs(kImageKinds.data(), to);
}

/// A command-line error: status 2.
struct UsageError {
  std::string message;
};

/// An input or output error: status 1; the message names the file (and line).
struct Failure {
  std::string message;
};

struct Options {
  fs::path manifest;
  fs::path output;
  glint::ToneMapping tone_mapping{.op = glint::ToneMapOperator::reinhard, .exposure = 0.0f};
  std::string baseline;
  std::string title = "glint: renders against a reference";
  std::string note;
};

Options parse_options(int argc, char** argv) {
  Options options;
  bool have_manifest = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      return argv[++i];
    };
    if (arg == "-o" || arg == "--output") {
      options.output = value();
    } else if (arg == "--tonemap") {
      const std::string_view name = value();
      const auto op = glint::parse_tone_map_operator(name);
      if (!op)
        throw UsageError{"--tonemap expects " + glint::tone_map_operator_list() + ", got '" +
                         std::string(name) + "'"};
      options.tone_mapping.op = *op;
    } else if (arg == "--exposure") {
      const std::string_view text = value();
      const std::optional<float> ev = glint::parse_exposure(text);
      if (!ev)
        throw UsageError{"--exposure expects " + glint::exposure_range_text() + ", got '" +
                         std::string(text) + "'"};
      options.tone_mapping.exposure = *ev;
    } else if (arg == "--baseline") {
      options.baseline = value();
    } else if (arg == "--title") {
      options.title = value();
    } else if (arg == "--note") {
      options.note = value();
    } else if (arg.starts_with("-") && arg != "-") {
      throw UsageError{"unknown option '" + std::string(arg) + "'"};
    } else if (have_manifest) {
      throw UsageError{"more than one manifest: '" + options.manifest.string() + "' and '" +
                       std::string(arg) + "'"};
    } else {
      options.manifest = arg;
      have_manifest = true;
    }
  }
  if (!have_manifest) throw UsageError{"no manifest given"};
  if (options.output.empty()) throw UsageError{"no output directory given (-o DIR)"};
  return options;
}

// ---------------------------------------------------------------------------------------------
// The manifest

struct Image {
  fs::path path;
  std::string where;  // "MANIFEST:LINE", for messages
  std::string description;
};

struct Variant : Image {
  std::string name;
  double cpu_seconds = 0.0;
  long spp = 0;
};

struct Scene {
  std::string name;
  std::optional<Image> reference;
  std::string first_mention;  // "MANIFEST:LINE" of the scene's first line
  std::vector<Variant> variants;
};

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', start);
    fields.push_back(line.substr(start, tab - start));
    if (tab == std::string::npos) return fields;
    start = tab + 1;
  }
}

// Scene and variant names become file names and URL parts: letters, digits, '.', '_', '-',
// not starting with '.', which keeps them inside DIR and needs no escaping anywhere.
bool is_plain_name(std::string_view name) {
  if (name.empty() || name.size() > 100 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

// A manifest names a few images a line. These bounds are far beyond any real one; what is not a
// manifest (/dev/zero, a line without end, a pipe that never ends) is refused once it passes
// them, before it takes the memory.
constexpr std::size_t kMaxManifestLineLength = std::size_t{1} << 16;
constexpr std::uint64_t kMaxManifestSize = std::uint64_t{1} << 24;

/// Reads the manifest a line at a time within its bounds.
class ManifestLines {
 public:
  explicit ManifestLines(const fs::path& manifest)
      : name_(manifest.string()), in_(manifest, [this](const std::string& problem) {
          throw Failure{"cannot read the manifest " + name_ + ": " + problem};
        }) {
    if (in_.size() && *in_.size() > kMaxManifestSize) too_large();
  }

  /// The next line, without its '\n', into `line`; false at the end of the file.
  bool next(std::string& line) {
    line.clear();
    ++number_;  // first, so that a file too large is named at the line that makes it so
    int c = get();
    if (c < 0) {
      --number_;
      return false;
    }
    for (; c >= 0 && c != '\n'; c = get()) {
      if (c == '\0') fail("line contains a NUL byte (is this a text file?)");
      if (line.size() == kMaxManifestLineLength)
        fail("line is longer than " + std::to_string(kMaxManifestLineLength) + " characters");
      line += char(c);
    }
    return true;
  }

  /// "MANIFEST:LINE" of the line last read.
  std::string where() const { return name_ + ":" + std::to_string(number_); }

 private:
  int get() {
    const int c = in_.get();
    if (in_.position() > kMaxManifestSize) too_large();
    return c;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw Failure{where() + ": " + problem};
  }
  [[noreturn]] void too_large() const {
    const std::string problem =
        "file is larger than " + std::to_string(kMaxManifestSize >> 20) + " MiB";
    throw Failure{number_ > 0 ? where() + ": " + problem : name_ + ": " + problem};
  }

  std::string name_;
  glint::InputFile in_;
  int number_ = 0;
};

std::vector<Scene> read_manifest(const fs::path& manifest) {
  ManifestLines lines(manifest);
  const fs::path base = manifest.parent_path();
  std::vector<Scene> scenes;
  std::string line;
  while (lines.next(line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const std::string where = lines.where();
    const auto fail = [&](const std::string& why) { throw Failure{where + ": " + why}; };
    const std::vector<std::string> f = split_tabs(line);
    const std::string& kind = f[0];
    std::size_t expected_min = 0;
    std::size_t expected_max = 0;
    if (kind == "reference") {
      expected_min = 3, expected_max = 4;
    } else if (kind == "variant") {
      expected_min = 6, expected_max = 7;
    } else {
      fail("a line starts with 'reference' or 'variant', not '" + kind + "'");
    }
    if (f.size() < expected_min || f.size() > expected_max)
      fail("a " + kind + " line has " + std::to_string(expected_min) + " to " +
           std::to_string(expected_max) + " tab-separated fields, this one " +
           std::to_string(f.size()));
    if (!is_plain_name(f[1]))
      fail("scene name '" + f[1] + "': use letters, digits, '.', '_' and '-' only");
    auto scene =
        std::find_if(scenes.begin(), scenes.end(), [&](const Scene& s) { return s.name == f[1]; });
    if (scene == scenes.end()) {
      Scene added;
      added.name = f[1];
      added.first_mention = where;
      scenes.push_back(std::move(added));
      scene = scenes.end() - 1;
    }
    const auto resolve = [&](const std::string& path) {
      if (path.empty()) fail("the image path is empty");
      const fs::path p(path);
      return p.is_absolute() ? p : base / p;
    };
    if (kind == "reference") {
      if (scene->reference)
        fail("a second reference for scene '" + f[1] + "' (the first is at " +
             scene->reference->where + ")");
      scene->reference = Image{resolve(f[2]), where, f.size() > 3 ? f[3] : ""};
      continue;
    }
    const std::string& name = f[2];
    if (!is_plain_name(name))
      fail("variant name '" + name + "': use letters, digits, '.', '_' and '-' only");
    for (const Variant& v : scene->variants)
      if (v.name == name)
        fail("variant '" + name + "' of scene '" + f[1] + "' is already at " + v.where);
    Variant variant;
    static_cast<Image&>(variant) = Image{resolve(f[3]), where, f.size() > 6 ? f[6] : ""};
    variant.name = name;
    const std::string& cpu = f[4];
    const auto [cpu_end, cpu_error] =
        std::from_chars(cpu.data(), cpu.data() + cpu.size(), variant.cpu_seconds);
    if (cpu_error != std::errc() || cpu_end != cpu.data() + cpu.size() ||
        !std::isfinite(variant.cpu_seconds) || variant.cpu_seconds < 0.0)
      fail("CPU seconds must be a number of at least 0, got '" + cpu + "'");
    const std::string& spp = f[5];
    const auto [spp_end, spp_error] =
        std::from_chars(spp.data(), spp.data() + spp.size(), variant.spp);
    if (spp_error != std::errc() || spp_end != spp.data() + spp.size() || variant.spp < 1)
      fail("samples per pixel must be a whole number of at least 1, got '" + spp + "'");
    scene->variants.push_back(std::move(variant));
  }
  if (scenes.empty()) throw Failure{manifest.string() + ": no images listed"};
  for (const Scene& scene : scenes)
    if (!scene.reference)
      throw Failure{scene.first_mention + ": scene '" + scene.name + "' has no reference line"};
  return scenes;
}

// ---------------------------------------------------------------------------------------------
// Images and numbers

glint::Film read_film(const fs::path& path) {
  const std::string extension = path.extension().string();
  if (extension == ".exr" || extension == ".EXR") {
#ifdef GLINT_HAVE_EXR
    return glint::read_exr(path).film;
#else
    throw glint::ImageReadError(path.string() +
                                ": an OpenEXR image, and this glint-compare was built without "
                                "OpenEXR (Debian: libopenexr-dev, scripts/install-deps --exr)");
#endif
  }
  return glint::read_pfm(path);
}

glint::Film read_image(const Image& image) {
  glint::Film film;
  try {
    film = read_film(image.path);
  } catch (const glint::Error& error) {
    throw Failure{image.where + ": " + error.what()};
  }
  for (const glint::Color& c : film.pixels())
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
      throw Failure{image.where + ": " + image.path.string() + " has NaN or infinite values"};
  return film;
}

/// The decades [low, high] (powers of ten) the error maps of one scene span: up to the 99th
/// percentile of all its variants' errors, rounded up to a decade, and four decades below.
/// One range for the whole scene, so that its maps compare with each other.
std::pair<int, int> error_decades(const std::vector<std::vector<float>>& maps) {
  constexpr int kDecades = 4;
  std::vector<float> positive;
  for (const auto& map : maps)
    for (const float v : map)
      if (v > 0.0f) positive.push_back(v);
  if (positive.empty()) return {-kDecades, 0};
  const std::size_t k = std::min(positive.size() - 1, positive.size() * 99 / 100);
  std::nth_element(positive.begin(), positive.begin() + std::ptrdiff_t(k), positive.end());
  const int high = int(std::ceil(std::log10(double(positive[k])) - 1e-9));
  return {high - kDecades, high};
}

std::vector<char> encode_error_png(const std::vector<float>& map, int width, int height,
                                   std::pair<int, int> decades) {
  return glint::encode_png_rgb8(
      width, height,
      glint::false_color_rgb8(map, std::pow(10.0, decades.first), std::pow(10.0, decades.second)));
}

// ---------------------------------------------------------------------------------------------
// JSON, read by the page with JSON.parse

std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string css_color(const glint::Rgb8& c) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

std::string tone_mapping_text(const glint::ToneMapping& tone_mapping) {
  std::ostringstream text;
  text << glint::name_of(tone_mapping.op) << ", exposure " << tone_mapping.exposure << " EV";
  return text.str();
}

std::vector<char> to_bytes(std::string_view text) {
  return {text.begin(), text.end()};
}

// ---------------------------------------------------------------------------------------------

void run(const Options& options) {
  const std::vector<Scene> scenes = read_manifest(options.manifest);

  // Everything is read, compared and encoded before anything is written.
  std::vector<glint::FileContents> files;
  std::ostringstream json;
  json << "{\"title\": " << glint::detail::json_string(options.title)
       << ", \"note\": " << glint::detail::json_string(options.note) << ", \"toneMapping\": "
       << glint::detail::json_string(tone_mapping_text(options.tone_mapping))
       << ", \"errorEpsilon\": " << json_number(glint::kRelativeErrorEpsilon) << ", \"ramp\": [";
  for (std::size_t i = 0; i < glint::kErrorRamp.size(); ++i)
    json << (i ? ", " : "") << glint::detail::json_string(css_color(glint::kErrorRamp[i]));
  json << "],\n\"scenes\": [";

  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const Scene& scene = scenes[s];
    const glint::Film reference = read_image(*scene.reference);
    const std::string reference_png = scene.name + "/reference.png";
    files.push_back(
        {options.output / reference_png, glint::encode_png(reference, options.tone_mapping)});

    std::vector<std::vector<float>> maps;
    std::vector<glint::ImageComparison> comparisons;
    for (const Variant& variant : scene.variants) {
      const glint::Film film = read_image(variant);
      if (film.width() != reference.width() || film.height() != reference.height())
        throw Failure{variant.where + ": " + variant.path.string() + " is " +
                      std::to_string(film.width()) + "x" + std::to_string(film.height()) +
                      ", the reference " + scene.reference->path.string() + " (" +
                      scene.reference->where + ") is " + std::to_string(reference.width()) + "x" +
                      std::to_string(reference.height())};
      comparisons.push_back(glint::compare_images(film, reference));
      maps.push_back(glint::relative_squared_error(film, reference));
      files.push_back({options.output / (scene.name + "/variant-" + variant.name + ".png"),
                       glint::encode_png(film, options.tone_mapping)});
    }
    const std::pair<int, int> decades = error_decades(maps);

    const bool has_baseline =
        options.baseline.empty()
            ? !scene.variants.empty()
            : std::any_of(scene.variants.begin(), scene.variants.end(),
                          [&](const Variant& v) { return v.name == options.baseline; });
    const std::string baseline = !has_baseline              ? ""
                                 : options.baseline.empty() ? scene.variants.front().name
                                                            : options.baseline;
    json << (s ? ",\n" : "") << "{\"name\": " << glint::detail::json_string(scene.name)
         << ", \"width\": " << reference.width() << ", \"height\": " << reference.height()
         << ", \"baseline\": " << (baseline.empty() ? "null" : glint::detail::json_string(baseline))
         << ", \"errorDecades\": [" << decades.first << ", " << decades.second << "]"
         << ", \"reference\": {\"image\": " << glint::detail::json_string(reference_png)
         << ", \"description\": " << glint::detail::json_string(scene.reference->description) << "}"
         << ", \"variants\": [";
    for (std::size_t v = 0; v < scene.variants.size(); ++v) {
      const Variant& variant = scene.variants[v];
      const std::string error_png = scene.name + "/error-" + variant.name + ".png";
      files.push_back({options.output / error_png,
                       encode_error_png(maps[v], reference.width(), reference.height(), decades)});
      double rel_mse = 0.0;
      for (const float e : maps[v])
        rel_mse += e;
      rel_mse /= double(maps[v].size());
      json << (v ? ",\n  " : "\n  ") << "{\"name\": " << glint::detail::json_string(variant.name)
           << ", \"description\": " << glint::detail::json_string(variant.description)
           << ", \"image\": "
           << glint::detail::json_string(scene.name + "/variant-" + variant.name + ".png")
           << ", \"errorImage\": " << glint::detail::json_string(error_png)
           << ", \"spp\": " << variant.spp << ", \"cpu\": " << json_number(variant.cpu_seconds)
           << ", \"rmse\": " << json_number(comparisons[v].rmse)
           << ", \"relativeRmse\": " << json_number(comparisons[v].relative_rmse())
           << ", \"relMse\": " << json_number(rel_mse) << "}";
    }
    json << "]}";
  }
  json << "]}\n";

  std::string page(glint_compare::kPageTemplate);
  const std::size_t marker = page.find(glint_compare::kDataMarker);
  page.replace(marker, glint_compare::kDataMarker.size(), json.str());
  // Last in the list, so renamed into place last: the page never refers to an image that is
  // not there yet.
  files.push_back({options.output / "index.html", to_bytes(page)});

  std::error_code error;
  for (const Scene& scene : scenes) {
    fs::create_directories(options.output / scene.name, error);
    if (error)
      throw Failure{"cannot make the directory " + (options.output / scene.name).string() + ": " +
                    error.message()};
  }
  try {
    glint::write_files(files);
  } catch (const glint::Error& write_error) {
    throw Failure{write_error.what()};
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      print_usage(stdout);
      return 0;
    }
  }
  try {
    const Options options = parse_options(argc, argv);
    run(options);
    std::printf("glint-compare: wrote %s\n", (options.output / "index.html").c_str());
    return 0;
  } catch (const UsageError& error) {
    std::fprintf(stderr, "glint-compare: %s\n", error.message.c_str());
    print_usage(stderr);
    return 2;
  } catch (const Failure& failure) {
    std::fprintf(stderr, "glint-compare: error: %s\n", failure.message.c_str());
    return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "glint-compare: error: %s\n", error.what());
    return 1;
  }
}
