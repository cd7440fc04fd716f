// Reading EXR files: layouts that glint does not write (offset data windows, half RGBA, tiles,
// 32-bit unsigned channels) are read; anything else (not EXR, truncated, damaged, not RGB,
// subsampled, too large) is a glint::ImageReadError naming the file, never a crash.

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfTiledOutputFile.h>

#include <Imath/half.h>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../unit/peak_memory.hpp"
#include "exr_test_support.hpp"
#include "glint/error.hpp"
#include "glint/exr/exr_image.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/texture_reader.hpp"

using namespace glint;
using exr_test::same_bits;
using exr_test::varied_film;
namespace fs = std::filesystem;

namespace {

std::vector<char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

/// One channel's values, row-major over the data window.
struct ChannelData {
  const char* name;
  Imf::PixelType type;
  std::vector<char> bytes;
  int sampling = 1;
};

/// Writes an EXR file with OpenEXR directly: the given channels over `window`, scan lines, or
/// 4x4 tiles.
void write_raw(const fs::path& path, const Imath::Box2i& window, std::vector<ChannelData>& channels,
               bool tiled = false) {
  Imf::Header header(window, window);
  const int width = window.max.x - window.min.x + 1;
  Imf::FrameBuffer frame;
  for (ChannelData& channel : channels) {
    header.channels().insert(channel.name,
                             Imf::Channel(channel.type, channel.sampling, channel.sampling));
    const std::size_t size = channel.type == Imf::HALF ? 2 : 4;
    frame.insert(channel.name, Imf::Slice::Make(channel.type, channel.bytes.data(), window, size,
                                                size * std::size_t(width / channel.sampling),
                                                channel.sampling, channel.sampling));
  }
  if (tiled) {
    header.setTileDescription(Imf::TileDescription(4, 4, Imf::ONE_LEVEL));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
  } else {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(window.max.y - window.min.y + 1);
  }
}

template <typename T>
std::vector<char> as_bytes(const std::vector<T>& values) {
  std::vector<char> bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

/// The message of the ImageReadError that decoding `bytes` throws, or "" if it decodes.
std::string decode_error(const std::vector<char>& bytes, const std::string& name) {
  try {
    decode_exr(bytes.data(), bytes.size(), name);
    return "";
  } catch (const ImageReadError& error) {
    return error.what();
  }
}

}  // namespace

TEST_CASE("EXR read: half RGBA over an offset data window, and tiles", "[exr]") {
  const exr_test::ScratchDirectory scratch("read-layouts");
  const Imath::Box2i window(Imath::V2i(10, -3), Imath::V2i(14, 3));  // 5 x 7 pixels
  std::vector<Imath::half> r, g, b, a;
  for (int i = 0; i < 35; ++i) {
    r.push_back(Imath::half(float(i)));
    g.push_back(Imath::half(float(i) * 0.5f));
    b.push_back(Imath::half(-float(i) / 64.0f));
    a.push_back(Imath::half(1.0f));
  }
  for (const bool tiled : {false, true}) {
    CAPTURE(tiled);
    std::vector<ChannelData> channels = {{"A", Imf::HALF, as_bytes(a)},
                                         {"B", Imf::HALF, as_bytes(b)},
                                         {"G", Imf::HALF, as_bytes(g)},
                                         {"R", Imf::HALF, as_bytes(r)}};
    const fs::path path = scratch.path() / "rgba.exr";
    write_raw(path, window, channels, tiled);
    const ExrImage image = read_exr(path);
    CHECK(image.pixel_type == ExrPixelType::float16);
    REQUIRE(image.film.width() == 5);
    REQUIRE(image.film.height() == 7);
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 5; ++x) {
        const float i = float(y * 5 + x);
        CHECK(image.film.at(x, y) == Color(i, i * 0.5f, -i / 64.0f));
      }
  }
}

TEST_CASE("EXR read: 32-bit unsigned and mixed channels are read as float32", "[exr]") {
  const exr_test::ScratchDirectory scratch("read-uint");
  const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(2, 1));
  std::vector<ChannelData> channels = {
      {"R", Imf::UINT, as_bytes(std::vector<std::uint32_t>{0, 1, 2, 3, 4, 16777216})},
      {"G", Imf::HALF, as_bytes(std::vector<Imath::half>(6, Imath::half(0.25f)))},
      {"B", Imf::FLOAT, as_bytes(std::vector<float>(6, 1e-30f))}};
  const fs::path path = scratch.path() / "mixed.exr";
  write_raw(path, window, channels);
  const ExrImage image = read_exr(path);
  CHECK(image.pixel_type == ExrPixelType::float32);
  CHECK(image.film.at(0, 0) == Color(0.0f, 0.25f, 1e-30f));
  CHECK(image.film.at(2, 1) == Color(16777216.0f, 0.25f, 1e-30f));
}

TEST_CASE("EXR read: an image that is not RGB, subsampled or too large is refused", "[exr]") {
  const exr_test::ScratchDirectory scratch("read-refused");
  SECTION("luminance only") {
    const fs::path path = scratch.path() / "grey.exr";
    std::vector<ChannelData> channels = {{"Y", Imf::FLOAT, as_bytes(std::vector<float>(4, 0.5f))}};
    write_raw(path, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(1, 1)), channels);
    CHECK_THROWS_AS(read_exr(path), ImageReadError);
    CHECK_THROWS_WITH(read_exr(path),
                      path.string() + ": not an RGB image: no channel R (channels: Y)");
  }
  SECTION("subsampled chroma") {
    const fs::path path = scratch.path() / "subsampled.exr";
    std::vector<ChannelData> channels = {
        {"R", Imf::FLOAT, as_bytes(std::vector<float>(16, 0.5f))},
        {"G", Imf::FLOAT, as_bytes(std::vector<float>(16, 0.5f))},
        {"B", Imf::FLOAT, as_bytes(std::vector<float>(4, 0.5f)), 2}};
    write_raw(path, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(3, 3)), channels);
    CHECK_THROWS_WITH(read_exr(path),
                      path.string() + ": channel B is subsampled, which glint does not read");
  }
  SECTION("wider than glint's largest image") {
    const fs::path path = scratch.path() / "wide.exr";
    const int width = (1 << 15) + 1;
    std::vector<ChannelData> channels;
    for (const char* name : {"R", "G", "B"})
      channels.push_back({name, Imf::HALF, as_bytes(std::vector<Imath::half>(width))});
    write_raw(path, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(width - 1, 0)), channels);
    CHECK_THROWS_WITH(read_exr(path),
                      Catch::StartsWith(path.string() + ": image size 32769x1 "
                                                        "is beyond glint's limits"));
  }
}

TEST_CASE("EXR read: a file that is not EXR, missing or truncated names the file", "[exr]") {
  const exr_test::ScratchDirectory scratch("read-errors");
  const fs::path text = scratch.path() / "scene.exr";
  write_bytes(text, {'s', 'p', 'h', 'e', 'r', 'e', ' ', '0', ' ', '0', ' ', '0', '\n'});
  CHECK_THROWS_AS(read_exr(text), ImageReadError);
  CHECK_THROWS_WITH(read_exr(text), text.string() + ": not an OpenEXR file");
  const fs::path empty = scratch.path() / "empty.exr";
  write_bytes(empty, {});
  CHECK_THROWS_WITH(read_exr(empty), empty.string() + ": not an OpenEXR file");
  const fs::path missing = scratch.path() / "missing.exr";
  CHECK_THROWS_WITH(read_exr(missing),
                    "cannot read " + missing.string() + ": No such file or directory");
  CHECK_THROWS_WITH(read_exr(scratch.path()),
                    "cannot read " + scratch.path().string() + ": it is a directory");

  // Cut after every byte: the header, the offset table, the pixels.
  const ExrEncoded encoded = encode_exr(varied_film(3, 7), {ExrPixelType::float32, {{"a", 1}}});
  const std::vector<char>& whole = encoded.bytes;
  const fs::path cut = scratch.path() / "cut.exr";
  for (std::size_t size = 0; size < whole.size(); ++size) {
    CAPTURE(size, whole.size());
    const std::vector<char> truncated(whole.begin(), whole.begin() + std::ptrdiff_t(size));
    const std::string message = decode_error(truncated, "cut.exr");
    REQUIRE_THAT(message, Catch::StartsWith("cut.exr: "));
  }
  write_bytes(cut, std::vector<char>(whole.begin(), whole.end() - 5));
  CHECK_THROWS_WITH(read_exr(cut), Catch::StartsWith(cut.string() + ": not a readable OpenEXR"));
}

TEST_CASE("EXR read: damaged bytes give an error or an image, never a crash", "[exr]") {
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::float16}) {
    const ExrEncoded encoded = encode_exr(varied_film(5, 19), {type, {{"glint/spp", 4}}});
    int errors = 0;
    for (std::size_t i = 0; i < encoded.bytes.size(); ++i) {
      for (const int change : {0x01, 0x80, 0xff}) {
        std::vector<char> damaged = encoded.bytes;
        damaged[i] = char(damaged[i] ^ change);
        CAPTURE(i, change);
        try {
          const ExrImage image = decode_exr(damaged.data(), damaged.size(), "damaged.exr");
          // What it reads is within glint's limits.
          REQUIRE(image.film.pixels().size() ==
                  std::size_t(image.film.width()) * std::size_t(image.film.height()));
        } catch (const ImageReadError& error) {
          REQUIRE_THAT(error.what(), Catch::StartsWith("damaged.exr: "));
          ++errors;
        }
      }
    }
    CHECK(errors > 0);
  }
}

TEST_CASE("EXR read: a header claiming a huge image is refused before any allocation", "[exr]") {
  std::vector<char> bytes = encode_exr(varied_film(1, 1)).bytes;
  // The data window's value: "dataWindow\0box2i\0", its size (16), then min x, min y, max x,
  // max y as little-endian 32-bit integers.
  const std::string key("dataWindow\0box2i\0", 17);
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  REQUIRE(at != bytes.end());
  const std::size_t max_y = std::size_t(at - bytes.begin()) + key.size() + 4 + 12;
  // (OpenEXR 3.1 would take 3.4 GB of memory for 2^30 lines before it finds the data missing.)
  for (const std::int32_t max : {1 << 30, 0x7fffffff, 40000, -5}) {
    CAPTURE(max);
    std::memcpy(&bytes[max_y], &max, 4);
    CHECK(decode_error(bytes, "huge.exr") ==
          "huge.exr: image size 1x" + std::to_string(std::int64_t{max} + 1) +
              " is beyond glint's limits (32768 pixels a side, 67108864 in all)");
  }
}

TEST_CASE("EXR read: tiles too small for their image are refused before any allocation", "[exr]") {
  const exr_test::ScratchDirectory scratch("read-tiles");
  const fs::path path = scratch.path() / "tiled.exr";
  std::vector<ChannelData> channels;
  for (const char* name : {"B", "G", "R"})
    channels.push_back({name, Imf::FLOAT, as_bytes(std::vector<float>(64, 1.0f))});
  const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(7, 7));
  write_raw(path, window, channels, true);
  std::vector<char> bytes = read_bytes(path);
  REQUIRE(read_exr(path).film.at(7, 7) == Color(1.0f));
  // 1x1 tiles ("tiles\0tiledesc\0", size 9, x size, y size, mode) in a 4096x4096 image
  // ("dataWindow\0box2i\0", size 16, min x, min y, max x, max y): 16 million tiles.
  const auto value_of = [&](const std::string& key) {
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    REQUIRE(at != bytes.end());
    return std::size_t(at - bytes.begin()) + key.size() + 4;
  };
  const std::int32_t one = 1, side = 4095;
  const std::size_t tiles = value_of(std::string("tiles\0tiledesc\0", 15));
  std::memcpy(&bytes[tiles], &one, 4);
  std::memcpy(&bytes[tiles + 4], &one, 4);
  const std::size_t data_window = value_of(std::string("dataWindow\0box2i\0", 17));
  std::memcpy(&bytes[data_window + 8], &side, 4);
  std::memcpy(&bytes[data_window + 12], &side, 4);
  CHECK(decode_error(bytes, "tiled.exr") ==
        "tiled.exr: tiles of 1x1 pixels in a 4096x4096 image: too many for glint");
}

TEST_CASE("EXR: the file's layout, as OpenEXR reads it", "[exr]") {
  const exr_test::ScratchDirectory scratch("layout");
  const fs::path path = scratch.path() / "layout.exr";
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::float16}) {
    write_exr(varied_film(6, 4), path, {type, {{"comments", std::string("a test")}}});
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const bool is_half = type == ExrPixelType::float16;
    CHECK(header.compression() == (is_half ? Imf::PIZ_COMPRESSION : Imf::ZIP_COMPRESSION));
    CHECK(header.lineOrder() == Imf::INCREASING_Y);
    CHECK(header.dataWindow() == Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(5, 3)));
    CHECK(header.displayWindow() == header.dataWindow());
    CHECK_FALSE(header.hasTileDescription());
    int channels = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it, ++channels)
      CHECK(it.channel().type == (is_half ? Imf::HALF : Imf::FLOAT));
    CHECK(channels == 3);
    // The standard attribute, as OpenEXR's own accessor sees it.
    const auto* comments = header.findTypedAttribute<Imf::StringAttribute>("comments");
    REQUIRE(comments);
    CHECK(comments->value() == "a test");
  }
}

TEST_CASE("EXR read: an attribute larger than the file is refused before any allocation", "[exr]") {
  std::vector<char> bytes =
      encode_exr(varied_film(2, 2), {ExrPixelType::float32, {{"comments", std::string("hi")}}})
          .bytes;
  const std::string key("comments\0string\0", 16);
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  REQUIRE(at != bytes.end());
  const std::size_t size_at = std::size_t(at - bytes.begin()) + key.size();
  // (OpenEXR 3.1 would allocate the string, 2 GB, before it finds the file too short.)
  const std::int32_t huge = 0x7fffffff;
  std::memcpy(&bytes[size_at], &huge, 4);
  CHECK(decode_error(bytes, "big.exr") ==
        "big.exr: damaged header: attribute 'comments' of 2147483647 bytes, more than the file "
        "holds");
}

TEST_CASE("EXR read: a header claiming more than the file holds costs a band, not the image",
          "[exr][hostile]") {
  const exr_test::ScratchDirectory scratch("read-claims");
  // A 1x1 image, float (ZIP) and half (PIZ), whose data window is made 8192x8192 (within
  // glint's limits: an 805 MB film): the file holds one pixel of the 67 million it claims.
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::float16}) {
    std::vector<char> bytes = encode_exr(varied_film(1, 1), {type, {}}).bytes;
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    REQUIRE(at != bytes.end());
    const std::size_t max_x = std::size_t(at - bytes.begin()) + key.size() + 4 + 8;
    const std::int32_t side = 8191;
    std::memcpy(&bytes[max_x], &side, 4);
    std::memcpy(&bytes[max_x + 4], &side, 4);
    // Room for the offset table of 8192 lines (OpenEXR refuses a file too short for it), but
    // for none of the pixels.
    bytes.resize(bytes.size() + 8192 * 8 + 4096);
    const fs::path path = scratch.path() / "claims.exr";
    write_bytes(path, bytes);
    const glint_test::ChildRun run = glint_test::run_in_child_above_baseline([&] {
      try {
        read_exr(path);
      } catch (const ImageReadError& error) {
        return std::string(error.what())
                           .rfind(path.string() + ": not a readable OpenEXR file", 0) == 0
                   ? 0
                   : 3;
      }
      return 4;
    });
    CHECK(run.status == 0);
    CHECK(run.peak_kb < 64 * 1024);
  }
  // A real image much larger than its file (constant, so ZIP takes it to almost nothing) is
  // read through the same check, whole.
  Film flat(2048, 1024);
  for (int y = 0; y < flat.height(); ++y)
    flat.at(5, y) = Color(float(y), 0.5f, 2.0f);
  const fs::path path = scratch.path() / "flat.exr";
  write_exr(flat, path);
  REQUIRE(fs::file_size(path) * 4 + (4u << 20) < 2048u * 1024u * 12u);
  const ExrImage back = read_exr(path);
  CHECK(same_bits(back.film, flat));
}

TEST_CASE("EXR read: devices that never end are refused from their first bytes", "[exr][hostile]") {
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    CAPTURE(device);
    const glint_test::ChildRun run = glint_test::run_in_child_above_baseline([&] {
      try {
        read_exr(device);
      } catch (const ImageReadError& error) {
        return std::string(error.what()) == std::string(device) + ": not an OpenEXR file" ? 0 : 3;
      }
      return 4;
    });
    CHECK(run.status == 0);
    CHECK(run.peak_kb < 64 * 1024);
  }
}

TEST_CASE("EXR textures: read_texture and a scene's background read EXR files once enabled",
          "[exr]") {
  const exr_test::ScratchDirectory scratch("texture");
  Film film(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      film.at(x, y) = Color(float(x) + 0.25f, float(y) * 40.0f, 1e-3f * float(x + y));
  write_exr(film, scratch.path() / "sky.exr");
  enable_exr_textures();
  const Texture texture = read_texture(scratch.path() / "sky.exr", "sky.exr");
  CHECK(texture.width() == 3);
  CHECK(texture.height() == 2);
  CHECK(texture.texels() == film.pixels());

  std::ofstream(scratch.path() / "scene.txt")
      << "background image=sky.exr scale=2\nsphere center=0,0,0 radius=1\n";
  const SceneDescription scene = read_scene_file(scratch.path() / "scene.txt");
  REQUIRE(scene.background_image);
  CHECK(scene.background_image->texels() == film.pixels());

  // A texel that is no radiance is refused, naming the file and the texel.
  film.at(1, 1) = Color(-1.0f, 0.0f, 0.0f);
  write_exr(film, scratch.path() / "negative.exr");
  CHECK_THROWS_WITH(read_texture(scratch.path() / "negative.exr", "negative.exr"),
                    Catch::Contains("negative.exr: texel (1, 1) is not a finite, non-negative"));
}
