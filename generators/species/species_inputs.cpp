#include "generators/species/species_inputs.h"

#include <functional>
#include <set>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "generators/core/text_file.h"

namespace forest {

namespace {

namespace fs = std::filesystem;

// A file reached by the walk is hashed whole; a runaway chain of references (a file naming
// itself under another name) stops here.
constexpr size_t kMaxSpeciesInputs = 4096;

void toml_strings(const toml::node& node, const std::function<void(const std::string&)>& visit) {
  if (auto* s = node.as_string()) {
    visit(s->get());
  } else if (auto* t = node.as_table()) {
    for (auto&& [k, v] : *t) toml_strings(v, visit);
  } else if (auto* a = node.as_array()) {
    for (auto&& v : *a) toml_strings(v, visit);
  }
}

void json_strings(const nlohmann::json& node, const std::function<void(const std::string&)>& visit) {
  if (node.is_string()) {
    visit(node.get<std::string>());
  } else if (node.is_structured()) {
    for (const auto& v : node) json_strings(v, visit);
  }
}

// The string values of a TOML or JSON file; nothing for other formats or unparsable text.
void file_strings(const fs::path& file, const std::string& bytes, const std::function<void(const std::string&)>& visit) {
  std::string ext = file.extension().string();
  if (ext == ".toml") {
    try {
      toml::table t = toml::parse(bytes, file.string());
      toml_strings(t, visit);
    } catch (const toml::parse_error&) {
    }
  } else if (ext == ".json") {
    nlohmann::json j = nlohmann::json::parse(bytes, nullptr, false);
    if (!j.is_discarded()) json_strings(j, visit);
  }
}

}  // namespace

std::vector<SpeciesInput> species_inputs(const fs::path& preset) {
  std::vector<SpeciesInput> inputs;
  inputs.push_back({preset, preset.filename().string(), read_text_file(preset, "species preset")});
  std::set<fs::path> seen;
  std::error_code ec;
  seen.insert(fs::weakly_canonical(preset, ec));
  const fs::path root = preset.parent_path();
  // Breadth first over the files found so far (inputs grows while it is walked).
  for (size_t i = 0; i < inputs.size() && inputs.size() < kMaxSpeciesInputs; ++i) {
    const fs::path folder = inputs[i].file.parent_path();
    std::vector<fs::path> found;
    file_strings(inputs[i].file, inputs[i].bytes, [&](const std::string& s) {
      if (s.empty() || s.size() > 1024 || s.find('\0') != std::string::npos) return;
      fs::path candidate = folder / s;
      std::error_code e;
      if (!fs::is_regular_file(candidate, e)) return;
      if (seen.insert(fs::weakly_canonical(candidate, e)).second) found.push_back(candidate);
    });
    for (const fs::path& f : found) {
      if (inputs.size() >= kMaxSpeciesInputs) break;
      std::string name = f.lexically_relative(root.empty() ? fs::path(".") : root).generic_string();
      inputs.push_back({f, name.empty() ? f.generic_string() : name, read_text_file(f, "species input")});
    }
  }
  return inputs;
}

}  // namespace forest
