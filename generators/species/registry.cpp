#include "generators/species/registry.h"

#include "generators/core/toml_reader.h"
#include "generators/tree/foliage.h"
#include "generators/tree/habit_ranges.h"
#include "generators/methods/lsystem/lsystem_method.h"
#include "generators/methods/particle_flow/particle_flow_method.h"
#include "generators/methods/visual_hull/visual_hull_method.h"
#include "generators/methods/silhouettes/silhouettes_method.h"
#include "generators/methods/sketch_mrf/sketch_mrf_method.h"
#include "generators/methods/mig/mig_method.h"
#include "generators/methods/mgv/mgv_method.h"
#include "generators/methods/magnetic/magnetic_method.h"
#include "generators/methods/plantons/plantons_method.h"

namespace forest {

namespace {

// Every modeling method, one line each (pointers: the entries live in the methods' files).
const MethodEntry* const kMethods[] = {
    &kLsystemMethod, &kParticleFlowMethod, &kVisualHullMethod, &kSketchMrfMethod, &kSilhouettesMethod,
    &kMigMethod,     &kMgvMethod,          &kMagneticMethod,   &kPlantonsMethod,
};

const MethodEntry* find_method(const std::string& id) {
  for (const MethodEntry* m : kMethods)
    if (id == m->id) return m;
  return nullptr;
}

std::string known_methods() {
  std::string known;
  for (const MethodEntry* m : kMethods) known += (known.empty() ? "" : ", ") + std::string(m->id);
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
  const MethodEntry* m = find_method(method);
  if (!m) root.fail("method", "unknown method '" + method + "' (known: " + known_methods() + ")");
  root.check_key_groups({kCommonSpeciesKeys, m->keys, kLookKeys, kFoliageKeys, kHabitKeys});
  root.string("name", "");  // type check before the (possibly long) skeleton pass
  uint64_t seed = options.seed.value_or(uint64_t(root.integer("seed", 1, 0, int64_t(1) << 53)));
  // The look before the skeleton: a bad colour fails at once, not after a long simulation.
  LookKeys look = read_look_keys(root);
  const FoliageKeys foliage = read_foliage_keys(root, look.leaf_shape);
  look.leaf_color = season_leaf_color(foliage, look.leaf_color);
  // The [habit] ranges are what the tree is measured against, not how it grows: checked
  // here (a bad range fails before the skeleton pass); methods read only their own keys.
  read_habit_ranges(root);
  Skeleton skeleton = m->skeleton(root, seed);
  // The shared foliage stage: every method's skeleton gets the same foliage model.
  if (skeleton.own_leaves)
    size_foliage(skeleton.graph, foliage, seed);
  else
    place_foliage(skeleton.graph, foliage, seed);
  if (skeleton.keep_leaves) skeleton.keep_leaves(skeleton.graph);
  ModelDescription d;
  d.method = m->id;
  d.species = root.string("name", species_name);
  d.seed = seed;
  d.parameters = toml_to_json(root.raw());
  d.method_meta = std::move(skeleton.meta);
  if (options.skeleton) *options.skeleton = skeleton.graph;
  return build_model(skeleton.graph, look, foliage.shoot, d);
}

}  // namespace

std::span<const MethodEntry* const> method_table() { return kMethods; }

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
  for (const MethodEntry* m : kMethods) ids.push_back(m->id);
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
  for (const MethodEntry* m : kMethods)
    if (m->make_inputs) m->make_inputs(dir / m->id);
}

}  // namespace forest
