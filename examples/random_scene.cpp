// glint-random-scene: writes a random scene in the glint format (the report's section 5).
//
// Exit status: 0 on success (also when not every sphere could be placed: a warning says how
// many were), 1 for bad parameters or an I/O error, 2 for a bad command line.

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

#include "glint/generate/random_scene.hpp"
#include "glint/io/scene_writer.hpp"

namespace {

constexpr std::string_view kProgram = "glint-random-scene";

void print_usage(std::ostream& out) {
  const glint::RandomSceneParameters d;
  out << "usage: " << kProgram << " [options] [-o OUT.scene]\n"
      << "\n"
      << "Writes a random scene: spheres in a cube room with red and green side walls, each\n"
      << "sphere as large as it can be (up to --max-radius) while any two spheres stay\n"
      << "disjoint or nested. The same options and seed always give the same file.\n"
      << "\n"
      << "options (defaults are the report's):\n"
      << "  --size S            side of the cube the spheres are placed in (" << d.domain_size
      << ")\n"
      << "  --count N           number of spheres (" << d.sphere_count << ")\n"
      << "  --diffuse P         probability of a diffuse sphere of random colour ("
      << d.diffuse_probability << ")\n"
      << "  --mirror P          probability of a mirror sphere (" << d.mirror_probability << ")\n"
      << "  --transparent P     probability of a glass sphere, index in [1.1, 1.9] ("
      << d.transparent_probability << ")\n"
      << "                      the three probabilities must sum to 1\n"
      << "  --min-radius R      smallest radius a sphere may get (" << d.min_radius << ")\n"
      << "  --max-radius R      largest radius (" << d.max_radius << ")\n"
      << "  --gap F             surfaces stay F * min-radius apart (" << d.gap_fraction << ")\n"
      << "  --attempts N        centres tried per sphere before giving it up (" << d.max_attempts
      << ")\n"
      << "  --seed N            random seed, a 64-bit unsigned integer (" << d.seed << ")\n"
      << "  -o, --output FILE   write to FILE (atomically: FILE.tmp, then renamed) instead\n"
      << "                      of standard output\n"
      << "  -h, --help          show this help\n"
      << "\n"
      << "exit status: 0 written (a warning on stderr if not every sphere fit), 1 bad\n"
      << "parameters or I/O error, 2 bad command line\n";
}

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << kProgram << ": " << message << "\n\n";
  print_usage(std::cerr);
  std::exit(2);
}

[[noreturn]] void error(const std::string& message) {
  std::cerr << kProgram << ": error: " << message << "\n";
  std::exit(1);
}

template <typename T>
T parse_number(std::string_view option, std::string_view text) {
  T value{};
  const char* const end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  const std::string what = std::is_floating_point_v<T> ? "a number" : "an integer";
  if (ec == std::errc::result_out_of_range)
    usage_error("option " + std::string(option) + " value '" + std::string(text) +
                "' is out of range");
  if (ec != std::errc{} || ptr != end || text.empty())
    usage_error("option " + std::string(option) + " needs " + what + ", got '" + std::string(text) +
                "'");
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value))
      usage_error("option " + std::string(option) + " needs a finite number, got '" +
                  std::string(text) + "'");
  }
  return value;
}

struct Options {
  glint::RandomSceneParameters parameters;
  std::optional<std::string> output;
};

Options parse_arguments(int argc, char** argv) {
  Options options;
  glint::RandomSceneParameters& p = options.parameters;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      print_usage(std::cout);
      std::exit(0);
    }
    // Both "--size 80" and "--size=80".
    std::optional<std::string_view> inline_value;
    if (arg.starts_with("--")) {
      if (const auto eq = arg.find('='); eq != std::string_view::npos) {
        inline_value = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
      }
    }
    const auto value = [&]() -> std::string_view {
      if (inline_value) return *inline_value;
      if (i + 1 >= argc) usage_error("option " + std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--size") {
      p.domain_size = parse_number<float>(arg, value());
    } else if (arg == "--count") {
      p.sphere_count = parse_number<int>(arg, value());
    } else if (arg == "--diffuse") {
      p.diffuse_probability = parse_number<float>(arg, value());
    } else if (arg == "--mirror") {
      p.mirror_probability = parse_number<float>(arg, value());
    } else if (arg == "--transparent") {
      p.transparent_probability = parse_number<float>(arg, value());
    } else if (arg == "--min-radius") {
      p.min_radius = parse_number<float>(arg, value());
    } else if (arg == "--max-radius") {
      p.max_radius = parse_number<float>(arg, value());
    } else if (arg == "--gap") {
      p.gap_fraction = parse_number<float>(arg, value());
    } else if (arg == "--attempts") {
      p.max_attempts = parse_number<int>(arg, value());
    } else if (arg == "--seed") {
      p.seed = parse_number<std::uint64_t>(arg, value());
    } else if (arg == "-o" || arg == "--output") {
      const std::string_view path = value();
      if (path.empty()) usage_error("option " + std::string(arg) + " needs a file name");
      options.output = std::string(path);
    } else if (inline_value) {
      usage_error("unknown option '" + std::string(arg) + "'");
    } else {
      usage_error(arg.starts_with("-") ? "unknown option '" + std::string(arg) + "'"
                                       : "unexpected argument '" + std::string(arg) + "'");
    }
  }
  return options;
}

/// Shortest text that reads back as the same float, so the header reproduces the file exactly.
std::string exact(float v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

/// A comment block that documents how to make the file again.
std::string header(const glint::RandomSceneParameters& p, const glint::RandomSceneResult& r) {
  std::ostringstream out;
  out << "# Generated by " << kProgram << " --size " << exact(p.domain_size) << " --count "
      << p.sphere_count << " --diffuse " << exact(p.diffuse_probability) << " --mirror "
      << exact(p.mirror_probability) << " --transparent " << exact(p.transparent_probability)
      << " --min-radius " << exact(p.min_radius) << " --max-radius " << exact(p.max_radius)
      << " --gap " << exact(p.gap_fraction) << " --attempts " << p.max_attempts << " --seed "
      << p.seed << "\n"
      << "# " << r.wall_count << " wall spheres, then " << r.placed << " of " << r.requested
      << " random spheres\n";
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_arguments(argc, argv);
  glint::RandomSceneResult result;
  try {
    result = glint::generate_random_scene(options.parameters);
  } catch (const std::invalid_argument& e) {
    // The library's messages start with "random scene: "; the program name says as much.
    std::string message = e.what();
    constexpr std::string_view prefix = "random scene: ";
    if (message.starts_with(prefix)) message.erase(0, prefix.size());
    error(message);
  } catch (const std::bad_alloc&) {
    error("out of memory for " + std::to_string(options.parameters.sphere_count) + " spheres");
  }
  if (!result.complete())
    std::cerr << kProgram << ": warning: placed only " << result.placed << " of "
              << result.requested
              << " spheres; use a larger --size, a smaller --min-radius, fewer spheres or more "
                 "--attempts\n";

  const std::string comment = header(options.parameters, result);
  if (!options.output) {
    std::cout << comment;
    glint::write_scene(std::cout, result.scene);
    std::cout.flush();
    if (!std::cout) error("cannot write to standard output");
    return 0;
  }

  std::filesystem::path target = *options.output;
  std::error_code ec;
  const auto status = std::filesystem::status(target, ec);  // follows symbolic links
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    // A device or a pipe (/dev/stdout, a FIFO) cannot be replaced by a rename, and must not
    // be: write into it directly.
    std::ofstream out(target, std::ios::binary);
    if (!out) error("cannot open " + target.string() + ": " + std::strerror(errno));
    out << comment;
    glint::write_scene(out, result.scene);
    out.close();
    if (!out) error("cannot write " + target.string() + ": " + std::strerror(errno));
    return 0;
  }
  // Renaming onto a symbolic link would replace the link; write to the file it names.
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(target, ec)))
    target = std::filesystem::weakly_canonical(target, ec);

  // Write beside the target and rename: the rename is atomic, so OUT is either the old file
  // or the complete new one, never a half-written scene.
  std::filesystem::path temporary = target;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) error("cannot create " + temporary.string() + ": " + std::strerror(errno));
    out << comment;
    glint::write_scene(out, result.scene);
    out.close();  // closing flushes, and a full disk may only show up here
    if (!out) {
      const std::string reason = std::strerror(errno);
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      error("cannot write " + temporary.string() + ": " + reason);
    }
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    error("cannot rename " + temporary.string() + " to " + target.string() + ": " + ec.message());
  }
  return 0;
}
