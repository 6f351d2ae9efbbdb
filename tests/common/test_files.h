// Files of the tests: the source tree, fresh temporary folders (one per process and name)
// and whole-file reads. Shared by the unit, GPU and CLI tests.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace forest::test {

inline const std::string kSourceDir = FOREST_SOURCE_DIR;

// An empty folder <temp>/<prefix>_<pid>[_<name>]: whatever an earlier run left there is removed.
inline std::filesystem::path fresh_temp_dir(const std::string& prefix, const std::string& name = "") {
  std::filesystem::path d =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + (name.empty() ? "" : "_" + name));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// The bytes of a file; empty when it cannot be read.
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace forest::test
