// A progress bar on stderr when it is a terminal; silent in pipes and logs.
#pragma once
#include <unistd.h>

#include <cstdio>
#include <string>

namespace forest::app {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label) : label_(std::move(label)), tty_(isatty(STDERR_FILENO)) {}
  ~ProgressBar() { finish(); }
  void update(double fraction) {
    if (!tty_) return;
    int filled = int(fraction * 30.0 + 0.5);
    std::fprintf(stderr, "\r%s [%-30s] %3d%%", label_.c_str(), std::string(size_t(filled), '#').c_str(),
                 int(fraction * 100.0 + 0.5));
    std::fflush(stderr);
    shown_ = true;
  }
  void relabel(std::string label) { label_ = std::move(label); }
  void finish() {
    if (shown_) std::fprintf(stderr, "\n");
    shown_ = false;
  }

 private:
  std::string label_;
  bool tty_;
  bool shown_ = false;
};

}  // namespace forest::app
