// Strict, typed access to a TOML document: every key is checked for type and range,
// unknown keys are errors, and every error names file, line and key (InputError).
#pragma once
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <toml++/toml.h>

#include "generators/core/input_error.h"

namespace forest {

// A view of one table of a parsed document, with its dotted path for messages.
class TomlTable {
 public:
  TomlTable(const toml::table& table, std::string file, std::string path)
      : table_(&table), file_(std::move(file)), path_(std::move(path)) {}

  bool has(std::string_view key) const { return table_->contains(key); }
  // Fails on any key not in `allowed`.
  void check_keys(std::initializer_list<std::string_view> allowed) const;
  // Fails on any key in none of the groups (a species: common keys, the method's, the look's).
  void check_key_groups(std::initializer_list<std::span<const std::string_view>> groups) const;

  double number(std::string_view key, double fallback, double lo, double hi) const;
  double number(std::string_view key, double lo, double hi) const;  // required
  int64_t integer(std::string_view key, int64_t fallback, int64_t lo, int64_t hi) const;
  int64_t integer(std::string_view key, int64_t lo, int64_t hi) const;  // required
  bool boolean(std::string_view key, bool fallback) const;
  std::string string(std::string_view key, std::string fallback) const;
  std::string string(std::string_view key) const;  // required
  std::string choice(std::string_view key, std::string fallback,
                     std::initializer_list<std::string_view> options) const;
  std::string choice(std::string_view key, std::string fallback, std::span<const std::string> options) const;
  glm::vec3 vec3(std::string_view key, glm::vec3 fallback, double lo, double hi) const;
  glm::vec3 vec3(std::string_view key, double lo, double hi) const;  // required
  // A required closed interval [a, b]: two numbers with lo <= a <= b <= hi.
  glm::dvec2 interval(std::string_view key, double lo, double hi) const;
  // A required file name, relative to this file's folder unless absolute; fails when there
  // is no such file (input files of a species: drawings, learned models).
  std::filesystem::path existing_file(std::string_view key) const;
  // Sub-table (optional: empty table view when absent unless required).
  std::optional<TomlTable> table(std::string_view key) const;
  // Array of tables ([[key]]); empty when absent.
  std::vector<TomlTable> tables(std::string_view key) const;

  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  int line_of(std::string_view key) const;
  std::string key_path(std::string_view key) const;
  const std::string& file() const { return file_; }
  const toml::table& raw() const { return *table_; }

 private:
  const toml::node& require(std::string_view key) const;
  double to_number(std::string_view key, const toml::node& n, double lo, double hi) const;

  const toml::table* table_;
  std::string file_;
  std::string path_;
};

// A parsed TOML file. Missing file, unreadable file or syntax error -> InputError.
class TomlDocument {
 public:
  static TomlDocument load(const std::filesystem::path& file);
  static TomlDocument parse(std::string_view text, const std::string& name);
  TomlTable root() const { return TomlTable(table_, name_, ""); }
  const std::string& name() const { return name_; }
  const std::string& text() const { return text_; }

 private:
  toml::table table_;
  std::string name_;
  std::string text_;
};

}  // namespace forest
