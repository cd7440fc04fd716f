// Prints what the scene reader accepts, from its own tables, for tests/docs/reference_test.bash:
// "statement NAME KEY..." for each statement and "shading KIND" for each shading kind. With a
// file argument, reads that scene file first and fails, printing the reader's error, if it is
// not valid.
#include <cstdio>
#include <string>

#include "glint/io/scene_reader.hpp"
#include "glint/scene/material.hpp"

int main(int argc, char** argv) {
  if (argc > 2) {
    std::fprintf(stderr, "usage: glint-scene-format-keys [SCENE]\n");
    return 2;
  }
  if (argc == 2) {
    try {
      (void)glint::read_scene_file(argv[1]);
    } catch (const glint::Error& error) {
      std::fprintf(stderr, "%s\n", error.what());
      return 1;
    }
  }
  for (const auto& statement : glint::scene_format_statements()) {
    std::string line = "statement " + std::string(statement.statement);
    for (const std::string_view key : statement.keys)
      line += " " + std::string(key);
    std::printf("%s\n", line.c_str());
  }
  for (int kind = 0; kind < glint::kShadingKindCount; ++kind) {
    const std::string name(glint::to_string(static_cast<glint::ShadingKind>(kind)));
    std::printf("shading %s\n", name.c_str());
  }
  return 0;
}
