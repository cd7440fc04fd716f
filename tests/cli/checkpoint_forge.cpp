// A checkpoint rewritten with another variant name, its hashes made whole again, as a
// hand-edited or hostile file would be (tests/cli's checkpoint cases):
//
//   glint-checkpoint-forge IN OUT VARIANT
//
// VARIANT may hold any bytes but NUL (up to the format's 64). Exit status 0 when OUT was
// written, 1 otherwise.

#include <exception>
#include <fstream>
#include <iostream>
#include <vector>

#include "glint/io/checkpoint.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: glint-checkpoint-forge IN OUT VARIANT\n";
    return 1;
  }
  try {
    glint::Checkpoint checkpoint = glint::read_checkpoint(argv[1]);
    checkpoint.key.variant = argv[3];
    const std::vector<char> bytes = glint::encode_checkpoint(checkpoint);
    std::ofstream out(argv[2], std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out.flush()) throw std::runtime_error(std::string("cannot write ") + argv[2]);
  } catch (const std::exception& error) {
    std::cerr << "glint-checkpoint-forge: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
