// libFuzzer target for the checkpoint reader (`--resume FILE` reads untrusted bytes). Its
// contract: a complete, undamaged checkpoint or a CheckpointError, never a crash, an
// out-of-bounds read, an overflow or an allocation beyond what the bytes describe. Each input
// is decoded twice: as it is, and with its trailing content hash recomputed, so that mutations
// reach the parser behind the hash check instead of all failing at it.
//
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DGLINT_BUILD_FUZZERS=ON
//   cmake --build build-fuzz --target glint-checkpoint-reader-fuzz
//   build-fuzz/tests/fuzz/glint-checkpoint-reader-fuzz -max_total_time=120 \
//       tests/fuzz/checkpoint-corpus

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "glint/io/checkpoint.hpp"

namespace {

void decode(const std::vector<char>& bytes) {
  try {
    const glint::Checkpoint c = glint::decode_checkpoint(bytes, "fuzz");
    // What the reader accepts describes itself consistently.
    if (c.sums.width() != c.key.width || c.sums.height() != c.key.height) std::abort();
    if (c.samples_per_pixel_done > c.key.samples_per_pixel) std::abort();
    if (c.sums.has_splats() &&
        (c.sums.splats().width() != c.key.width || c.sums.splats().height() != c.key.height))
      std::abort();
  } catch (const glint::CheckpointError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<char> bytes(data, data + size);
  decode(bytes);
  if (bytes.size() >= 8) {
    const std::uint64_t hash = glint::fnv1a(bytes.data(), bytes.size() - 8);
    for (int i = 0; i < 8; ++i)
      bytes[bytes.size() - 8 + std::size_t(i)] = static_cast<char>(hash >> (8 * i));
    decode(bytes);
  }
  return 0;
}
