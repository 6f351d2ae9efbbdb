// Bad user input (files, flags, numbers): reported as one line naming file, line and key,
// and mapped to exit code 2 by the CLI. Everything else that throws is an internal failure.
#pragma once
#include <stdexcept>
#include <string>

namespace forest {

struct InputError : std::runtime_error {
  InputError(const std::string& file, int line, const std::string& key, const std::string& what)
      : std::runtime_error(format(file, line, key, what)) {}
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  static std::string format(const std::string& file, int line, const std::string& key,
                            const std::string& what) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    s += ": ";
    if (!key.empty()) s += key + ": ";
    s += what;
    // One line, always: flatten any newline a library put in its message.
    for (char& c : s)
      if (c == '\n' || c == '\r') c = ' ';
    return s;
  }
};

}  // namespace forest
