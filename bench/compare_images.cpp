// glint-compare-images: the error of one linear-radiance image against another, for the
// variant quality study (bench/run-all) and anyone comparing renders.
//
//   glint-compare-images TEST.pfm REFERENCE.pfm
//
// prints one line of key=value pairs, e.g.
//
//   rmse=0.0123 relative_rmse=0.0456 mean_reference=0.27 width=128 height=128
//
// rmse is over every pixel and channel of the linear radiance; relative_rmse is rmse divided by
// the reference's mean value (over pixels and channels), so that scenes of different brightness
// compare. Exit status: 0 compared, 1 unreadable file, size mismatch or non-finite values,
// 2 bad command line.

#include <cstddef>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "glint/image/compare.hpp"
#include "glint/io/image_reader.hpp"

namespace {

constexpr std::string_view kUsage =
    "usage: glint-compare-images TEST.pfm REFERENCE.pfm\n"
    "prints rmse=... relative_rmse=... (rmse / mean of REFERENCE) mean_reference=... width=...\n"
    "height=... over all pixels and channels of the linear radiance\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::string_view(argv[1]) == "-h" || std::string_view(argv[1]) == "--help")) {
    std::fputs(kUsage.data(), stdout);
    return 0;
  }
  if (argc != 3) {
    std::fprintf(stderr, "glint-compare-images: expected two PFM files\n%s", kUsage.data());
    return 2;
  }
  try {
    const glint::Film test = glint::read_pfm(argv[1]);
    const glint::Film reference = glint::read_pfm(argv[2]);
    if (test.width() != reference.width() || test.height() != reference.height()) {
      std::fprintf(stderr, "glint-compare-images: error: size mismatch: %s is %dx%d, %s is %dx%d\n",
                   argv[1], test.width(), test.height(), argv[2], reference.width(),
                   reference.height());
      return 1;
    }
    const glint::ImageComparison result = glint::compare_images(test, reference);
    if (result.non_finite > 0) {
      std::fprintf(stderr,
                   "glint-compare-images: error: %zu values are NaN or infinite (in %s or %s)\n",
                   result.non_finite, argv[1], argv[2]);
      return 1;
    }
    // A black reference has no relative error: nan says so rather than inf.
    std::printf("rmse=%.6g relative_rmse=%.6g mean_reference=%.6g width=%d height=%d\n",
                result.rmse, result.relative_rmse(), result.mean_reference, test.width(),
                test.height());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "glint-compare-images: error: %s\n", error.what());
    return 1;
  }
}
