#include "generators/species/registry.h"

#include "generators/core/toml_reader.h"
#include "generators/methods/lsystem/lsystem_method.h"
#include "generators/methods/particle_flow/particle_flow_method.h"
#include "generators/methods/visual_hull/visual_hull_method.h"
#include "generators/methods/silhouettes/silhouettes_method.h"
#include "generators/methods/sketch_mrf/sketch_mrf_method.h"
#include "generators/methods/mig/mig_method.h"
#include "generators/methods/mgv/mgv_method.h"
#include "generators/methods/magnetic/magnetic_method.h"
#include "generators/model/model_builder.h"
#include "generators/methods/plantons/plantons_method.h"
#include "generators/methods/plantons/plantons_samples.h"

namespace forest {

namespace {

// Every modeling method, one line each.
const MethodEntry kMethods[] = {
    {"lsystem", generate_lsystem, lsystem_default_species_text, nullptr},
    {"particle-flow", generate_particle_flow, particle_flow_default_species_text, particle_flow_make_inputs},
    {"visual-hull", generate_visual_hull, visual_hull_default_species_text, visual_hull_make_inputs},
    {"sketch-mrf", generate_sketch_mrf, sketch_mrf_default_species_text, sketch_mrf_make_inputs},
    {"silhouettes", generate_silhouettes, silhouettes_default_species_text, silhouettes_make_inputs},
    {"mig", generate_mig, mig_default_species_text, nullptr},
    {"mgv", generate_mgv, mgv_default_species_text, nullptr},
    {"magnetic", generate_magnetic, magnetic_default_species_text, nullptr},
    {"plantons", generate_plantons, plantons_default_species_text, plantons_make_inputs},
};

const MethodEntry* find_method(const std::string& id) {
  for (const MethodEntry& m : kMethods)
    if (id == m.id) return &m;
  return nullptr;
}

std::string known_methods() {
  std::string known;
  for (const MethodEntry& m : kMethods) known += (known.empty() ? "" : ", ") + std::string(m.id);
  return known;
}

TreeModel generate(const TomlDocument& doc, const std::string& species_name,
                   const GenerateOptions& options) {
  TomlTable root = doc.root();
  std::string method = root.string("method");
  // `method` comes first so a reader (and the error for a wrong one) sees the method at once.
  int method_line = root.line_of("method");
  for (auto&& [key, value] : root.raw())
    if (int(key.source().begin.line) < method_line)
      throw InputError(doc.name(), int(key.source().begin.line), std::string(key.str()),
                       "`method` must be the first key of a species file");
  if (const MethodEntry* m = find_method(method)) {
    SkeletonCapture capture(options.skeleton);
    return m->generate(root, species_name, options);
  }
  root.fail("method", "unknown method '" + method + "' (known: " + known_methods() + ")");
}

}  // namespace

std::span<const MethodEntry> method_table() { return kMethods; }

TreeModel generate_from_species(const std::filesystem::path& species_file,
                                const GenerateOptions& options) {
  TomlDocument doc = TomlDocument::load(species_file);
  return generate(doc, species_file.stem().string(), options);
}

TreeModel generate_from_species_text(const std::string& text, const std::string& name,
                                     const GenerateOptions& options) {
  TomlDocument doc = TomlDocument::parse(text, name);
  return generate(doc, std::filesystem::path(name).stem().string(), options);
}

std::vector<std::string> method_ids() {
  std::vector<std::string> ids;
  for (const MethodEntry& m : kMethods) ids.push_back(m.id);
  return ids;
}

std::string default_species_text(const std::string& method) {
  if (const MethodEntry* m = find_method(method)) return m->default_species_text();
  throw InputError("", 0, "--method", "unknown method '" + method + "' (known: " + known_methods() + ")");
}

void make_inputs(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create folder: " + ec.message());
  for (const MethodEntry& m : kMethods)
    if (m.make_inputs) m.make_inputs(dir / m.id);
}

}  // namespace forest
