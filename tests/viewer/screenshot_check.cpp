// glint-viewer-screenshot-check: figures about a browser's screenshot of glint-compare's page,
// for tests/viewer/viewer_test.bash to judge whether the page showed what it should.
//
//   glint-viewer-screenshot-check SCREENSHOT.png [IMAGE.png]
//
// prints one line: width=W height=H colours=N dominant=F [image_colours=K found=G]
//   colours   distinct colours in the screenshot (a blank page has one or two)
//   dominant  the share of the screenshot's pixels that its most common colour covers
//   found     the share of IMAGE's distinct colours that appear somewhere in the screenshot:
//             the page draws images with image-rendering: pixelated, so a shown image puts its
//             exact colours on the screen, and one that is not shown finds almost none
// Exit status: 0 measured, 1 an unreadable image, 2 bad command line.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include "stb_image.h"

namespace {

struct Pixels {
  int width = 0;
  int height = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data{nullptr, stbi_image_free};
};

bool load(const char* path, Pixels& pixels) {
  int channels = 0;
  pixels.data.reset(stbi_load(path, &pixels.width, &pixels.height, &channels, 3));
  if (!pixels.data) {
    std::fprintf(stderr, "glint-viewer-screenshot-check: cannot read %s: %s\n", path,
                 stbi_failure_reason());
    return false;
  }
  return true;
}

std::uint32_t colour(const Pixels& pixels, long i) {
  const unsigned char* p = pixels.data.get() + 3 * i;
  return std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fputs("usage: glint-viewer-screenshot-check SCREENSHOT.png [IMAGE.png]\n", stderr);
    return 2;
  }
  Pixels shot;
  if (!load(argv[1], shot)) return 1;
  const long count = long(shot.width) * shot.height;
  std::unordered_map<std::uint32_t, long> histogram;
  for (long i = 0; i < count; ++i)
    ++histogram[colour(shot, i)];
  long most = 0;
  for (const auto& [c, n] : histogram)
    if (n > most) most = n;
  std::printf("width=%d height=%d colours=%zu dominant=%.4f", shot.width, shot.height,
              histogram.size(), count > 0 ? double(most) / double(count) : 1.0);
  if (argc == 3) {
    Pixels image;
    if (!load(argv[2], image)) return 1;
    std::unordered_set<std::uint32_t> wanted;
    for (long i = 0; i < long(image.width) * image.height; ++i)
      wanted.insert(colour(image, i));
    long found = 0;
    for (const std::uint32_t c : wanted)
      found += histogram.count(c) ? 1 : 0;
    std::printf(" image_colours=%zu found=%.4f", wanted.size(),
                wanted.empty() ? 0.0 : double(found) / double(wanted.size()));
  }
  std::printf("\n");
  return 0;
}
