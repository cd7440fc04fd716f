#pragma once
// A fresh directory for a test's files, one per test and process under the system's temporary
// directory, removed with its contents at the end.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace glint_test {

class ScratchDirectory {
 public:
  /// The directory glint-NAME-PID, emptied if it was left behind.
  explicit ScratchDirectory(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("glint-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace glint_test
