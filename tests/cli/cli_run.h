// The harness of the CLI tests: build/forest run in a shell as a user would, with stdout and
// stderr captured, from a fresh folder per test.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/common/test_files.h"

namespace forest::test {

struct Result {
  int code = -1;  // exit status; -1 when the process did not exit normally
  std::string out, err;
};

// `'build/forest' ARGS`, ready for a shell.
inline std::string forest_command(const std::string& args) { return "'" + std::string(FOREST_EXE) + "' " + args; }

// Runs a shell command without stdin; its stdout and stderr go through `dir`/stdout and `dir`/stderr.
inline Result run_captured(const std::string& command, const std::filesystem::path& dir) {
  std::string cmd = command + " >'" + (dir / "stdout").string() + "' 2>'" + (dir / "stderr").string() + "' </dev/null";
  int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "stdout");
  r.err = slurp(dir / "stderr");
  return r;
}

inline size_t lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

// A fixture with an empty folder of its own per test, <temp>/forest_<suite>_<pid>_<test>,
// removed after the test.
class CliDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fresh_temp_dir(std::string("forest_") + info->test_suite_name(), info->name());
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
};

}  // namespace forest::test
