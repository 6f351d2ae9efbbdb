#include "generators/core/toml_reader.h"

#include <cmath>
#include <sstream>

#include "generators/core/text_file.h"

namespace forest {

namespace {
std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}
std::string fmt_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

std::string TomlTable::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

int TomlTable::line_of(std::string_view key) const {
  auto it = table_->find(key);
  if (it != table_->end()) {
    if (it->first.source().begin.line) return int(it->first.source().begin.line);
    return int(it->second.source().begin.line);
  }
  return int(table_->source().begin.line);
}

void TomlTable::fail(std::string_view key, const std::string& what) const {
  throw InputError(file_, line_of(key), key_path(key), what);
}

void TomlTable::check_keys(std::initializer_list<std::string_view> allowed) const {
  check_key_groups({std::span<const std::string_view>(allowed.begin(), allowed.size())});
}

void TomlTable::check_key_groups(std::initializer_list<std::span<const std::string_view>> groups) const {
  for (auto&& [k, v] : *table_) {
    bool ok = false;
    for (auto group : groups)
      for (auto a : group) ok = ok || a == k.str();
    if (!ok) {
      std::string list;
      for (auto group : groups)
        for (auto a : group) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(file_, int(k.source().begin.line), key_path(k.str()),
                       "unknown key (expected one of: " + list + ")");
    }
  }
}

const toml::node& TomlTable::require(std::string_view key) const {
  const toml::node* n = table_->get(key);
  if (!n) fail(key, "missing required key");
  return *n;
}

double TomlTable::to_number(std::string_view key, const toml::node& n, double lo,
                            double hi) const {
  double v;
  if (auto i = n.as_integer())
    v = double(i->get());
  else if (auto f = n.as_floating_point())
    v = f->get();
  else
    fail(key, "expected a number, got " + type_name(n));
  if (!std::isfinite(v)) fail(key, "must be a finite number, got " + fmt_number(v));
  if (v < lo || v > hi)
    fail(key, "must be in [" + fmt_number(lo) + ", " + fmt_number(hi) + "], got " + fmt_number(v));
  return v;
}

double TomlTable::number(std::string_view key, double fallback, double lo, double hi) const {
  const toml::node* n = table_->get(key);
  return n ? to_number(key, *n, lo, hi) : fallback;
}

double TomlTable::number(std::string_view key, double lo, double hi) const {
  return to_number(key, require(key), lo, hi);
}

int64_t TomlTable::integer(std::string_view key, int64_t fallback, int64_t lo, int64_t hi) const {
  return has(key) ? integer(key, lo, hi) : fallback;
}

int64_t TomlTable::integer(std::string_view key, int64_t lo, int64_t hi) const {
  const toml::node& n = require(key);
  auto i = n.as_integer();
  if (!i) {
    if (auto f = n.as_floating_point())
      fail(key, "expected an integer, got " + fmt_number(f->get()));
    fail(key, "expected an integer, got " + type_name(n));
  }
  int64_t v = i->get();
  if (v < lo || v > hi)
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                  std::to_string(v));
  return v;
}

bool TomlTable::boolean(std::string_view key, bool fallback) const {
  const toml::node* n = table_->get(key);
  if (!n) return fallback;
  auto b = n->as_boolean();
  if (!b) fail(key, "expected true or false, got " + type_name(*n));
  return b->get();
}

std::string TomlTable::string(std::string_view key, std::string fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string TomlTable::string(std::string_view key) const {
  const toml::node& n = require(key);
  auto s = n.as_string();
  if (!s) fail(key, "expected a string, got " + type_name(n));
  return s->get();
}

std::string TomlTable::choice(std::string_view key, std::string fallback,
                              std::initializer_list<std::string_view> options) const {
  std::vector<std::string> list(options.begin(), options.end());
  return choice(key, std::move(fallback), list);
}

std::string TomlTable::choice(std::string_view key, std::string fallback, std::span<const std::string> options) const {
  std::string v = string(key, fallback);
  std::string list;
  for (const std::string& o : options) {
    if (o == v) return v;
    list += (list.empty() ? "" : ", ") + o;
  }
  fail(key, "'" + v + "' is not one of: " + list);
}

glm::vec3 TomlTable::vec3(std::string_view key, glm::vec3 fallback, double lo, double hi) const {
  return has(key) ? vec3(key, lo, hi) : fallback;
}

glm::vec3 TomlTable::vec3(std::string_view key, double lo, double hi) const {
  const toml::node& n = require(key);
  auto a = n.as_array();
  if (!a || a->size() != 3) fail(key, "expected an array of 3 numbers");
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = float(to_number(key, *a->get(size_t(i)), lo, hi));
  return v;
}

glm::dvec2 TomlTable::interval(std::string_view key, double lo, double hi) const {
  const toml::node& n = require(key);
  auto a = n.as_array();
  if (!a || a->size() != 2) fail(key, "expected [low, high], an array of 2 numbers");
  glm::dvec2 v(to_number(key, *a->get(0), lo, hi), to_number(key, *a->get(1), lo, hi));
  if (v.x > v.y) fail(key, "low " + fmt_number(v.x) + " is above high " + fmt_number(v.y));
  return v;
}

std::filesystem::path TomlTable::existing_file(std::string_view key) const {
  std::filesystem::path file = string(key);
  if (file.is_relative()) file = std::filesystem::path(file_).parent_path() / file;
  if (!std::filesystem::exists(file)) fail(key, "no such file '" + file.string() + "'");
  return file;
}

std::optional<TomlTable> TomlTable::table(std::string_view key) const {
  const toml::node* n = table_->get(key);
  if (!n) return std::nullopt;
  auto t = n->as_table();
  if (!t) fail(key, "expected a table, got " + type_name(*n));
  return TomlTable(*t, file_, key_path(key));
}

std::vector<TomlTable> TomlTable::tables(std::string_view key) const {
  std::vector<TomlTable> out;
  const toml::node* n = table_->get(key);
  if (!n) return out;
  auto a = n->as_array();
  if (!a) fail(key, "expected an array of tables ([[" + std::string(key) + "]])");
  for (size_t i = 0; i < a->size(); ++i) {
    auto t = a->get(i)->as_table();
    if (!t) fail(key, "expected an array of tables ([[" + std::string(key) + "]])");
    out.emplace_back(*t, file_, key_path(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

TomlDocument TomlDocument::load(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string(), 0, "", "file not found");
  if (std::filesystem::is_directory(file, ec))
    throw InputError(file.string(), 0, "", "is a directory, expected a TOML file");
  return parse(read_text_file(file), file.string());
}

TomlDocument TomlDocument::parse(std::string_view text, const std::string& name) {
  TomlDocument doc;
  doc.name_ = name;
  doc.text_ = std::string(text);
  try {
    doc.table_ = toml::parse(doc.text_, name);
  } catch (const toml::parse_error& e) {
    throw InputError(name, int(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  return doc;
}

}  // namespace forest
