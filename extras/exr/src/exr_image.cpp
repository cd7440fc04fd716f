// glint::exr: a Film to and from OpenEXR, through OpenEXR's C++ library (Imf).

#include "glint/exr/exr_image.hpp"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfVersion.h>

#include <Iex.h>
#include <Imath/half.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

#include "glint/error.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/input_file.hpp"
#include "glint/io/texture_reader.hpp"
#include "glint/scene/image_settings.hpp"

namespace glint {

namespace {

static_assert(sizeof(Color) == 3 * sizeof(float) && std::is_same_v<decltype(Color::x), float>,
              "the Film's pixels are three packed floats");

// Compression: lossless, as a linear image must be (B44, DWA and PXR24 would break the exact
// round trip), deterministic (the same film gives the same bytes), and read by every EXR
// reader. Which one was measured on glint's renders (640x480, 16 spp, and 320x240 at 512):
// - float32: ZIP (zlib on blocks of 16 scan lines after OpenEXR's byte reordering). Rendered
//   float radiance hardly compresses (the low mantissa bits are noise): ZIP took 2-4% off,
//   PIZ 0-3% in twice the time (70 ms against 120 ms for 640x480 here). Flat regions (a black
//   background) still shrink to almost nothing.
// - float16: PIZ (wavelet and Huffman), which suits 16-bit data: 28-47% off, 5% smaller than
//   ZIP and faster to write (15 ms against 25 ms).
Imf::Compression compression_of(ExrPixelType type) {
  return type == ExrPixelType::float16 ? Imf::PIZ_COMPRESSION : Imf::ZIP_COMPRESSION;
}

// Attributes that make up the file's structure: the required ones, and those of tiled,
// multi-part, deep and multi-view files. A caller's attribute may not take these names.
constexpr std::string_view kStructuralNames[] = {"channels",
                                                 "compression",
                                                 "dataWindow",
                                                 "displayWindow",
                                                 "lineOrder",
                                                 "pixelAspectRatio",
                                                 "screenWindowCenter",
                                                 "screenWindowWidth",
                                                 "tiles",
                                                 "type",
                                                 "name",
                                                 "version",
                                                 "chunkCount",
                                                 "maxSamplesPerPixel",
                                                 "view",
                                                 "multiView"};

bool is_structural(std::string_view name) {
  return std::find(std::begin(kStructuralNames), std::end(kStructuralNames), name) !=
         std::end(kStructuralNames);
}

/// OpenEXR's standard attributes (ImfStandardAttributes.h) of the four types this library
/// writes, with their type's index in ExrAttributeValue: readers expect exactly that type.
struct StandardAttribute {
  std::string_view name;
  std::size_t type;
};
constexpr std::size_t kFloat = 1, kString = 3;
constexpr StandardAttribute kStandardAttributes[] = {{"whiteLuminance", kFloat},
                                                     {"renderingTransform", kString},
                                                     {"lookModTransform", kString},
                                                     {"xDensity", kFloat},
                                                     {"owner", kString},
                                                     {"comments", kString},
                                                     {"capDate", kString},
                                                     {"utcOffset", kFloat},
                                                     {"longitude", kFloat},
                                                     {"latitude", kFloat},
                                                     {"altitude", kFloat},
                                                     {"focus", kFloat},
                                                     {"expTime", kFloat},
                                                     {"aperture", kFloat},
                                                     {"isoSpeed", kFloat},
                                                     {"wrapmodes", kString}};
constexpr std::string_view kTypeNames[] = {"an int", "a float", "a double", "a string"};

/// An attribute's name as a message can show it: control bytes as '?', and shortened.
std::string printable(std::string_view name) {
  std::string shown = std::string(name.substr(0, 64)) + (name.size() > 64 ? "..." : "");
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return shown;
}

[[noreturn]] void refuse_attribute(const std::string& name, const std::string& why) {
  throw ImageWriteError("EXR attribute '" + printable(name) + "': " + why);
}

void insert_attributes(Imf::Header& header, const std::vector<ExrAttribute>& attributes) {
  for (const ExrAttribute& attribute : attributes) {
    const std::string& name = attribute.name;
    if (name.empty()) refuse_attribute(name, "the name is empty");
    if (name.size() > 255) refuse_attribute(name, "the name is longer than 255 bytes");
    if (name.find('\0') != std::string::npos) refuse_attribute(name, "the name holds a NUL");
    if (is_structural(name)) refuse_attribute(name, "the name is one of the file's structure");
    if (header.find(name) != header.end()) refuse_attribute(name, "given twice");
    for (const StandardAttribute& standard : kStandardAttributes)
      if (standard.name == name && standard.type != attribute.value.index())
        refuse_attribute(name, "OpenEXR's standard attribute of that name is " +
                                   std::string(kTypeNames[standard.type]));
    std::visit(
        [&](const auto& value) {
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, int>)
            header.insert(name, Imf::IntAttribute(value));
          else if constexpr (std::is_same_v<T, float>)
            header.insert(name, Imf::FloatAttribute(value));
          else if constexpr (std::is_same_v<T, double>)
            header.insert(name, Imf::DoubleAttribute(value));
          else
            header.insert(name, Imf::StringAttribute(value));
        },
        attribute.value);
  }
}

/// An OStream that appends to a vector; OpenEXR seeks back to fill in the offset table.
class MemoryOStream final : public Imf::OStream {
 public:
  explicit MemoryOStream(std::vector<char>& bytes) : Imf::OStream("<memory>"), bytes_(bytes) {}

  void write(const char c[], int n) override {
    if (n < 0) throw Iex::ArgExc("negative write size");
    const std::size_t end = position_ + std::size_t(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::copy(c, c + n, bytes_.begin() + std::ptrdiff_t(position_));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = std::size_t(position); }

 private:
  std::vector<char>& bytes_;
  std::size_t position_ = 0;
};

/// An IStream over bytes in memory. Reading past the end throws, as OpenEXR expects.
class MemoryIStream final : public Imf::IStream {
 public:
  MemoryIStream(const char* data, std::size_t size, const std::string& name)
      : Imf::IStream(name.c_str()), data_(data), size_(size) {}

  bool read(char c[], int n) override {
    if (n < 0 || position_ > size_ || std::size_t(n) > size_ - position_)
      throw Iex::InputExc("unexpected end of file");
    std::copy(data_ + position_, data_ + position_ + n, c);
    position_ += std::size_t(n);
    return position_ < size_;
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override {
    position_ = std::size_t(std::min<std::uint64_t>(position, size_ + 1));
  }

 private:
  const char* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

/// A film value as a half: beyond the largest finite half (infinities included) it is that
/// half, with the sign kept, and counted.
Imath::half to_half(float value, std::size_t& clamped) {
  if (std::fabs(value) > kExrLargestHalf) {  // false for NaN, which stays NaN
    ++clamped;
    return Imath::half(std::copysign(kExrLargestHalf, value));
  }
  return Imath::half(value);
}

/// Why an image of the data window [min, max] is beyond glint's limits, or "".
std::string size_problem(std::int64_t min_x, std::int64_t min_y, std::int64_t max_x,
                         std::int64_t max_y) {
  const std::int64_t width = max_x - min_x + 1, height = max_y - min_y + 1;
  if (width >= 1 && height >= 1 && width <= limits::max_image_side &&
      height <= limits::max_image_side && width * height <= limits::max_image_pixels)
    return "";
  return "image size " + std::to_string(width) + "x" + std::to_string(height) +
         " is beyond glint's limits (" + std::to_string(limits::max_image_side) +
         " pixels a side, " + std::to_string(limits::max_image_pixels) + " in all)";
}

/// Looks through the headers of an EXR file (every part's, in a multi-part file) for data
/// windows and tile sizes beyond glint's limits, before OpenEXR reads them: it sizes its tables
/// of chunk offsets from them, and a damaged or hostile header would make it allocate
/// gigabytes; a damaged attribute size likewise. Returns why the file is refused, or "".
/// Anything else it does not understand is left for OpenEXR to report. (Header layout: the 4-byte
/// magic number, 4 bytes of version and flags, then attributes as name, NUL, type name, NUL, 32-bit
/// little-endian size and value, ended by an empty name; in a multi-part file, more headers follow
/// until an empty one.) `size` is at least 8.
std::string header_problem(const char* data, std::size_t size) {
  std::size_t position = 8;
  const auto text = [&]() -> std::optional<std::string_view> {
    const std::size_t start = position;
    while (position < size && position - start < 256 && data[position] != '\0')
      ++position;
    if (position >= size || data[position] != '\0') return std::nullopt;
    return std::string_view(data + start, position++ - start);
  };
  const auto int32_at = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (int byte = 3; byte >= 0; --byte)
      value = value << 8 | static_cast<unsigned char>(data[at + std::size_t(byte)]);
    return std::int64_t(std::int32_t(value));
  };
  const bool multi_part = (static_cast<unsigned char>(data[5]) & 0x10) != 0;
  for (bool first = true; first || multi_part; first = false) {
    std::int64_t width = 0, height = 0, tile_width = 0, tile_height = 0;
    for (int attributes = 0;; ++attributes) {
      const std::optional<std::string_view> name = text();
      if (!name) return "";
      if (name->empty()) {
        if (attributes == 0) return "";  // the empty header that ends a multi-part file
        break;
      }
      const std::optional<std::string_view> type = text();
      if (!type || size - position < 4) return "";
      const std::int64_t value_size = int32_at(position);
      position += 4;
      // OpenEXR allocates the value before it finds the file too short for it.
      if (value_size < 0 || std::uint64_t(value_size) > size - position)
        return "damaged header: attribute '" + printable(*name) + "' of " +
               std::to_string(value_size) + " bytes, more than the file holds";
      if (*name == "dataWindow" && *type == "box2i" && value_size == 16) {
        const std::int64_t min_x = int32_at(position), min_y = int32_at(position + 4),
                           max_x = int32_at(position + 8), max_y = int32_at(position + 12);
        if (std::string problem = size_problem(min_x, min_y, max_x, max_y); !problem.empty())
          return problem;
        width = max_x - min_x + 1;
        height = max_y - min_y + 1;
      } else if (*name == "tiles" && *type == "tiledesc" && value_size == 9) {
        tile_width = std::int64_t(std::uint32_t(int32_at(position)));
        tile_height = std::int64_t(std::uint32_t(int32_at(position + 4)));
      }
      position += std::size_t(value_size);
    }
    // More than 4 million tiles (an offset each: 1x1 tiles over a large image) are refused; the
    // largest image glint makes, in OpenEXR's usual 64x64 tiles, has 16384.
    if (width > 0 && tile_width > 0 && tile_height > 0 &&
        ((width + tile_width - 1) / tile_width) * ((height + tile_height - 1) / tile_height) >
            limits::max_image_pixels / 16)
      return "tiles of " + std::to_string(tile_width) + "x" + std::to_string(tile_height) +
             " pixels in a " + std::to_string(width) + "x" + std::to_string(height) +
             " image: too many for glint";
  }
  return "";
}

/// Above this many times the file's size (plus a band), an image's pixels are read once before
/// its film is allocated: an uncompressed float image is as large as its film, a half one half
/// as large; lossless compression of rendered images takes a few percent.
constexpr std::uint64_t kExrDirectRatio = 4;
/// The bytes of film a band of check_pixels holds.
constexpr std::uint64_t kExrBandBytes = std::uint64_t{4} << 20;

/// Decodes every pixel of `window` in bands of about kExrBandBytes, keeping none: throws
/// OpenEXR's exception where the file lacks or damages some of them.
void check_pixels(Imf::InputFile& file, const Imath::Box2i& window) {
  const int width = window.max.x - window.min.x + 1;
  const int rows = int(std::max<std::uint64_t>(1, kExrBandBytes / (sizeof(Color) * width)));
  std::vector<Color> band(std::size_t(width) * std::size_t(rows));
  for (int y = window.min.y; y <= window.max.y; y += rows) {
    const int last = std::min(window.max.y, y + rows - 1);
    const Imath::Box2i lines(Imath::V2i(window.min.x, y), Imath::V2i(window.max.x, last));
    char* base = reinterpret_cast<char*>(band.data());
    Imf::FrameBuffer frame;
    const char* names[] = {"R", "G", "B"};
    for (std::size_t i = 0; i < 3; ++i)
      frame.insert(names[i], Imf::Slice::Make(Imf::FLOAT, base + i * sizeof(float), lines,
                                              sizeof(Color), sizeof(Color) * std::size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(y, last);
  }
}

}  // namespace

ExrEncoded encode_exr(const Film& film, const ExrWriteOptions& options) {
  const int width = film.width(), height = film.height();
  if (width < 1 || height < 1)
    throw ImageWriteError("EXR encoding of an empty " + std::to_string(width) + "x" +
                          std::to_string(height) + " image");
  const bool is_half = options.pixel_type == ExrPixelType::float16;
  const Imf::PixelType type = is_half ? Imf::HALF : Imf::FLOAT;
  ExrEncoded encoded;
  std::vector<Imath::half> halves;
  const char* base = reinterpret_cast<const char*>(film.pixels().data());
  std::size_t size = sizeof(float);
  if (is_half) {
    halves.reserve(film.pixels().size() * 3);
    for (const Color& c : film.pixels())
      for (const float v : {c.x, c.y, c.z})
        halves.push_back(to_half(v, encoded.clamped_values));
    base = reinterpret_cast<const char*>(halves.data());
    size = sizeof(Imath::half);
  }
  try {
    Imf::Header header(width, height, 1.0f, Imath::V2f(0.0f, 0.0f), 1.0f, Imf::INCREASING_Y,
                       compression_of(options.pixel_type));
    Imf::FrameBuffer frame;
    const char* names[] = {"R", "G", "B"};
    for (std::size_t i = 0; i < 3; ++i) {
      header.channels().insert(names[i], Imf::Channel(type));
      // OpenEXR only reads the pixels it writes, although Slice takes a non-const pointer.
      frame.insert(names[i], Imf::Slice(type, const_cast<char*>(base + i * size), 3 * size,
                                        3 * size * std::size_t(width)));
    }
    insert_attributes(header, options.attributes);
    MemoryOStream stream(encoded.bytes);
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
    // The table of chunk offsets is written by the destructor, at the end of this scope.
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {
    throw ImageWriteError("EXR encoding of a " + std::to_string(width) + "x" +
                          std::to_string(height) + " image failed: " + error.what());
  }
  return encoded;
}

std::size_t write_exr(const Film& film, const std::filesystem::path& path,
                      const ExrWriteOptions& options) {
  ExrEncoded encoded;
  try {
    encoded = encode_exr(film, options);
  } catch (const ImageWriteError& error) {
    throw ImageWriteError("cannot write " + path.string() + ": " + error.what());
  }
  write_files({{path, std::move(encoded.bytes)}});
  return encoded.clamped_values;
}

const ExrAttribute* ExrImage::find(const std::string& name) const {
  for (const ExrAttribute& attribute : attributes)
    if (attribute.name == name) return &attribute;
  return nullptr;
}

ExrImage decode_exr(const char* data, std::size_t size, const std::string& name) {
  const auto fail = [&](const std::string& why) -> void {
    throw ImageReadError(name + ": " + why);
  };
  if (size < 8 || !Imf::isImfMagic(data)) fail("not an OpenEXR file");
  if (const std::string problem = header_problem(data, size); !problem.empty()) fail(problem);
  try {
    MemoryIStream stream(data, size, name);
    Imf::InputFile file(stream);
    const Imf::Header& header = file.header();

    const Imath::Box2i window = header.dataWindow();
    if (const std::string problem =
            size_problem(window.min.x, window.min.y, window.max.x, window.max.y);
        !problem.empty())
      fail(problem);
    const int width = window.max.x - window.min.x + 1;

    const Imf::ChannelList& channels = header.channels();
    ExrImage image;
    int halves = 0;
    for (const char* channel : {"R", "G", "B"}) {
      const Imf::Channel* found = channels.findChannel(channel);
      if (!found) {
        std::string names;
        for (auto it = channels.begin(); it != channels.end(); ++it)
          names += std::string(names.empty() ? "" : ", ") + it.name();
        fail("not an RGB image: no channel " + std::string(channel) +
             " (channels: " + (names.empty() ? "none" : names) + ")");
      }
      if (found->xSampling != 1 || found->ySampling != 1)
        fail("channel " + std::string(channel) + " is subsampled, which glint does not read");
      if (found->type == Imf::HALF) ++halves;
    }
    image.pixel_type = halves == 3 ? ExrPixelType::float16 : ExrPixelType::float32;

    const int height = window.max.y - window.min.y + 1;
    // An image much larger than the file (a short file whose header claims a large image, or
    // one that compresses very well) is decoded once, in bands, before its film is allocated:
    // a header that lies then costs a band, not the image it claims.
    if (std::uint64_t(width) * std::uint64_t(height) * sizeof(Color) >
        kExrDirectRatio * std::uint64_t(size) + kExrBandBytes)
      check_pixels(file, window);
    image.film = Film(width, height);
    char* base = reinterpret_cast<char*>(&image.film.at(0, 0));
    Imf::FrameBuffer frame;
    const char* names[] = {"R", "G", "B"};
    for (std::size_t i = 0; i < 3; ++i)
      frame.insert(names[i], Imf::Slice::Make(Imf::FLOAT, base + i * sizeof(float), window,
                                              sizeof(Color), sizeof(Color) * std::size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);

    for (auto it = header.begin(); it != header.end(); ++it) {
      const std::string attribute = it.name();
      if (is_structural(attribute)) continue;
      const Imf::Attribute& value = it.attribute();
      if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&value))
        image.attributes.push_back({attribute, i->value()});
      else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&value))
        image.attributes.push_back({attribute, f->value()});
      else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&value))
        image.attributes.push_back({attribute, d->value()});
      else if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&value))
        image.attributes.push_back({attribute, s->value()});
    }
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {
    // OpenEXR's exceptions (Iex::BaseExc), and std::bad_alloc on absurd sizes in damaged data.
    fail(std::string("not a readable OpenEXR file: ") + error.what());
  }
  return {};  // not reached: fail throws
}

ExrImage read_exr(const std::filesystem::path& path) {
  const std::string name = path.string();
  InputFile file(path, [&](const std::string& why) {
    throw ImageReadError("cannot read " + name + ": " + why);
  });
  // The magic number first: a file of another kind, or a device such as /dev/zero, is refused
  // before the rest is read.
  std::vector<char> bytes(4);
  if (file.read(bytes.data(), bytes.size()) < bytes.size() || !Imf::isImfMagic(bytes.data()))
    throw ImageReadError(name + ": not an OpenEXR file");
  const std::string limit = std::to_string(kMaxExrFileSize >> 20) + " MiB";
  if (const std::optional<std::uint64_t> left = file.remaining()) {
    if (*file.size() > kMaxExrFileSize)
      file.fail("it has " + std::to_string(*file.size()) + " bytes, more than glint reads (" +
                limit + ")");
    if (!file.append(bytes, *left)) file.fail("it shrank while being read");
  } else if (file.append(bytes, kMaxExrFileSize - bytes.size()) && !file.at_end()) {
    file.fail("it holds more than glint reads (" + limit + "): is it an endless stream?");
  }
  return decode_exr(bytes.data(), bytes.size(), name);
}

void enable_exr_textures() {
  exr_texture_reader() = [](const std::filesystem::path& path) {
    const ExrImage image = read_exr(path);
    DecodedTexels decoded{image.film.width(), image.film.height(), {}};
    decoded.rgb.reserve(image.film.pixels().size() * 3);
    for (const Color& c : image.film.pixels()) {
      decoded.rgb.push_back(c.r);
      decoded.rgb.push_back(c.g);
      decoded.rgb.push_back(c.b);
    }
    return decoded;
  };
}

}  // namespace glint
