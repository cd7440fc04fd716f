// glint-random-scene: writes a random scene in the glint format (the report's section 5).
// The usage text (print_usage) lists the options and the exit statuses.

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <variant>
#include <vector>

#include "cpu_check.hpp"  // before main: this CPU has what the build uses
#include "glint/detail/text.hpp"
#include "glint/generate/random_scene.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/scene_writer.hpp"

namespace {

constexpr std::string_view kProgram = "glint-random-scene";

using Parameters = glint::RandomSceneParameters;

/// Shortest text that reads back as the same float, so that a header comment reproduces its
/// file exactly.
std::string shortest(float v) {
  return glint::detail::format_number(v);
}

/// A command-line option that sets one generator parameter.
struct ParameterOption {
  std::string_view name;
  std::string_view value_name;
  std::variant<float Parameters::*, int Parameters::*, std::uint64_t Parameters::*> member;
  std::string help;       ///< the usage line, which ends with the default in parentheses
  std::string note = {};  ///< a further usage line, if any
};

/// The options that set parameters: their parsing, their usage lines and the header comment
/// that records how a file was made all come from this one list, in this order.
const std::vector<ParameterOption>& parameter_options() {
  static const std::vector<ParameterOption> options = {
      {"--size", "S", &Parameters::domain_size, "side of the cube the spheres are placed in"},
      {"--count", "N", &Parameters::sphere_count, "number of spheres"},
      {"--diffuse", "P", &Parameters::diffuse_probability,
       "probability of a diffuse sphere of random colour"},
      {"--mirror", "P", &Parameters::mirror_probability, "probability of a mirror sphere"},
      {"--transparent", "P", &Parameters::transparent_probability,
       "probability of a glass sphere, index in [" +
           shortest(float(glint::kRandomIor.low_value())) + ", " +
           shortest(float(glint::kRandomIor.high_value())) + "]",
       "the three probabilities must sum to 1"},
      {"--min-radius", "R", &Parameters::min_radius, "smallest radius a sphere may get"},
      {"--max-radius", "R", &Parameters::max_radius, "largest radius"},
      {"--gap", "F", &Parameters::gap_fraction, "surfaces stay F * min-radius apart"},
      {"--attempts", "N", &Parameters::max_attempts,
       "centres tried per sphere before giving it up"},
      {"--seed", "N", &Parameters::seed, "random seed, a 64-bit unsigned integer"},
  };
  return options;
}

/// The option's value in `p`, as the command line would give it.
std::string value_text(const Parameters& p, const ParameterOption& option) {
  return std::visit(
      [&](auto member) {
        const auto value = p.*member;
        if constexpr (std::is_floating_point_v<decltype(value)>)
          return shortest(value);
        else
          return std::to_string(value);
      },
      option.member);
}

void print_usage(std::ostream& out) {
  const auto line = [&](std::string_view left, std::string_view text) {
    constexpr std::size_t kTextColumn = 22;
    std::string start = "  ";
    start += left;
    start.resize(std::max(kTextColumn, start.size() + 1), ' ');
    out << start << text << "\n";
  };
  out << "usage: " << kProgram << " [options] [-o OUT.scene]\n"
      << "\n"
      << "Writes a random scene: spheres in a cube room with red and green side walls, each\n"
      << "sphere as large as it can be (up to --max-radius) while any two spheres stay\n"
      << "disjoint or nested. The same options and seed always give the same file.\n"
      << "\n"
      << "options (defaults are the report's):\n";
  const Parameters defaults;
  for (const ParameterOption& option : parameter_options()) {
    line(std::string(option.name) + " " + std::string(option.value_name),
         option.help + " (" + value_text(defaults, option) + ")");
    if (!option.note.empty()) line("", option.note);
  }
  line("-o, --output FILE", "write to FILE instead of standard output: to a new file");
  line("", "beside it, renamed over it once complete");
  line("-h, --help", "show this help");
  out << "\n"
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

void set_parameter(Parameters& p, const ParameterOption& option, std::string_view text) {
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(p.*member)>;
        p.*member = parse_number<T>(option.name, text);
      },
      option.member);
}

const ParameterOption* find_parameter_option(std::string_view name) {
  for (const ParameterOption& option : parameter_options())
    if (option.name == name) return &option;
  return nullptr;
}

struct Options {
  Parameters parameters;
  std::optional<std::string> output;
};

Options parse_arguments(int argc, char** argv) {
  Options options;
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
    if (const ParameterOption* option = find_parameter_option(arg)) {
      set_parameter(options.parameters, *option, value());
    } else if (arg == "-o" || arg == "--output") {
      const std::string_view path = value();
      if (path.empty()) usage_error("option " + std::string(arg) + " needs a file name");
      options.output = std::string(path);
    } else if (inline_value || arg.starts_with("-")) {
      usage_error("unknown option '" + std::string(arg) + "'");
    } else {
      usage_error("unexpected argument '" + std::string(arg) + "'");
    }
  }
  return options;
}

glint::RandomSceneResult generate(const Parameters& p) {
  try {
    return glint::generate_random_scene(p);
  } catch (const glint::RandomSceneError& e) {
    error(e.problem());
  } catch (const std::bad_alloc&) {
    error("out of memory for " + std::to_string(p.sphere_count) + " spheres");
  }
}

void warn_if_incomplete(const glint::RandomSceneResult& result) {
  if (result.complete()) return;
  std::cerr << kProgram << ": warning: placed only " << result.placed << " of " << result.requested
            << " spheres; use a larger --size, a smaller --min-radius, fewer spheres or more "
               "--attempts\n";
}

/// A comment block that documents how to make the file again.
std::string header(const Parameters& p, const glint::RandomSceneResult& r) {
  std::ostringstream out;
  out << "# Generated by " << kProgram;
  for (const ParameterOption& option : parameter_options())
    out << " " << option.name << " " << value_text(p, option);
  out << "\n"
      << "# " << r.wall_count << " wall spheres, then " << r.placed << " of " << r.requested
      << " random spheres\n";
  return out.str();
}

/// The file's contents: the header comment, then the scene.
struct SceneFile {
  std::string comment;
  const glint::SceneDescription& scene;
  void write(std::ostream& out) const {
    out << comment;
    glint::write_scene(out, scene);
  }
};

void write_to_standard_output(const SceneFile& file) {
  file.write(std::cout);
  std::cout.flush();
  if (!std::cout) error("cannot write to standard output");
}

/// For a device or a pipe (/dev/stdout, a FIFO), which a rename cannot replace, and must not.
void write_in_place(const std::filesystem::path& target, const SceneFile& file) {
  std::ofstream out(target, std::ios::binary);
  if (!out) error("cannot open " + target.string() + ": " + std::strerror(errno));
  file.write(out);
  out.close();
  if (!out) error("cannot write " + target.string() + ": " + std::strerror(errno));
}

/// Writes through a temporary beside the target (glint::StagedFile, as glint-render does: an
/// unpredictable name, created with O_EXCL | O_NOFOLLOW, so that nothing planted beside the
/// target is written through), renamed over the target once complete: the target is either the
/// old file or the whole new one, never a half-written scene, and a failure leaves no temporary.
void write_staged(const std::filesystem::path& target, const SceneFile& file) {
  try {
    glint::StagedFile staged(target);
    staged.append(file.comment.data(), file.comment.size());
    glint::write_scene_in_pieces(
        file.scene, [&](std::string_view text) { staged.append(text.data(), text.size()); });
    staged.finish();
    staged.commit();
  } catch (const glint::Error& e) {
    error(e.what());  // the temporary is gone with `staged`
  }
}

/// Where -o FILE goes.
struct Destination {
  std::filesystem::path path;
  bool in_place = false;  ///< a device or a pipe (/dev/stdout, a FIFO), which a rename cannot
                          ///< replace, and must not
};

/// Resolves and checks -o FILE before the scene is generated, so that a mistyped output fails
/// at once, and clears what a killed run of the same output left beside it.
Destination prepare_output(const std::string& output) {
  Destination destination{output};
  std::error_code ec;
  const auto status = std::filesystem::status(destination.path, ec);  // follows symbolic links
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    destination.in_place = true;
    return destination;
  }
  // Renaming onto a symbolic link would replace the link; write to the file it names.
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(destination.path, ec)))
    destination.path = std::filesystem::weakly_canonical(destination.path, ec);
  try {
    glint::check_output_path(destination.path);
  } catch (const glint::Error& e) {
    error(e.what());
  }
  glint::remove_stale_temporaries(destination.path);
  return destination;
}

void write_output(const std::optional<Destination>& destination, const SceneFile& file) {
  if (!destination) return write_to_standard_output(file);
  if (destination->in_place) return write_in_place(destination->path, file);
  write_staged(destination->path, file);
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_arguments(argc, argv);
  std::optional<Destination> destination;
  if (options.output) destination = prepare_output(*options.output);
  const glint::RandomSceneResult result = generate(options.parameters);
  warn_if_incomplete(result);
  write_output(destination, SceneFile{header(options.parameters, result), result.scene});
  return 0;
}
