#include "engine/tools/bake/species_cache.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "engine/tools/bake/build_identity.h"
#include "engine/tools/bake/cache_record.h"
#include "engine/tools/bake/tree_bake.h"
#include "engine/vk/context.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/content_hash.h"
#include "generators/species/registry.h"
#include "generators/species/species_inputs.h"

namespace forest {

namespace fs = std::filesystem;

namespace {

// The device that measured an entry's tables: name and driver (VK_KHR_driver_properties,
// core in Vulkan 1.2).
void describe_device(const vk::Context& ctx, CacheRecord& r) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(ctx.physical, &p);
  r.device = p.properties.deviceName;
  r.driver = std::string(driver.driverName) + " " + driver.driverInfo;
}

void bake_with(vk::Context* ctx, TreeModel& model, const TreeBakeSettings& settings, CacheRecord& record) {
  if (ctx) {
    bake_tree_model(*ctx, model, settings);
    describe_device(*ctx, record);
    return;
  }
  vk::Context own;
  vk::ContextOptions o;
  o.validation = vk::validation_from_env();
  try {
    vk::create_context(own, o);
    bake_tree_model(own, model, settings);
    describe_device(own, record);
  } catch (...) {
    vk::destroy_context(own);
    throw;
  }
  vk::destroy_context(own);
}

}  // namespace

std::filesystem::path default_cache_dir() {
  if (const char* c = std::getenv("FOREST_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "forest";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "forest";
  return ".forest-cache";
}

SpeciesKey species_key(const SpeciesDesc& species, const BakeDesc& bake) {
  SpeciesKey k;
  std::vector<SpeciesInput> inputs = species_inputs(species.preset);
  ContentHash h;
  // The layout of the key itself; what the code does is in the build identity.
  h.add("forest species cache key 2");
  h.add(bake_build_identity());
  for (const SpeciesInput& i : inputs) {
    // Names relative to the preset's folder and contents: a moved or renamed project keeps
    // its entries, an edited mask does not.
    std::string hash = content_hash(i.bytes);
    h.add(i.file == species.preset ? std::string("preset") : i.name);
    h.add(hash);
    std::error_code ec;
    fs::path abs = fs::weakly_canonical(fs::absolute(i.file, ec), ec);
    k.inputs.push_back({i.name, abs.generic_string(), hash});
  }
  h.add(species.seed ? "seed " + std::to_string(*species.seed) : "preset seed");
  h.add("bake " + bake.priority + " " + std::to_string(bake.views) + " " + std::to_string(bake.resolution) +
        (bake.impostor ? "" : " no impostor"));
  k.key = h.hex();
  return k;
}

std::string species_cache_key(const SpeciesDesc& species, const BakeDesc& bake) { return species_key(species, bake).key; }

fs::path species_cache_file(const SpeciesDesc& species, const std::string& key, const fs::path& cache_dir) {
  return cache_dir / (species.preset.stem().string() + "-" + key + ".glb");
}

CachedSpecies load_or_bake_species(const SpeciesDesc& species, const BakeDesc& bake,
                                   const fs::path& cache_dir, vk::Context* ctx,
                                   const std::function<void(double)>& progress) {
  CachedSpecies out;
  SpeciesKey key = species_key(species, bake);
  out.file = species_cache_file(species, key.key, cache_dir);
  std::error_code ec;
  if (fs::is_regular_file(out.file, ec)) {
    try {
      out.model = load_glb(out.file);
      out.hit = true;
      return out;
    } catch (const InputError&) {
      // A damaged cache entry (disk full, killed writer on a filesystem without atomic
      // rename): rebuild it below.
    }
  }
  fs::create_directories(cache_dir, ec);
  if (ec) throw InputError(cache_dir.string(), 0, "FOREST_CACHE", "cannot create cache folder: " + ec.message());

  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  GenerateOptions options;
  options.seed = species.seed;
  out.model = generate_from_species(species.preset, options);
  auto t1 = clock::now();
  TreeBakeSettings settings;
  settings.priority = bake.priority;
  settings.views = bake.views;
  settings.resolution = bake.resolution;
  settings.impostor = bake.impostor;
  if (progress) settings.progress = progress;
  CacheRecord record;
  bake_with(ctx, out.model, settings, record);
  out.generate_seconds = std::chrono::duration<double>(t1 - t0).count();
  out.bake_seconds = std::chrono::duration<double>(clock::now() - t1).count();
  std::vector<uint8_t> bytes = encode_glb(out.model);
  record.key = key.key;
  record.preset = key.inputs.front().file;
  record.seed = species.seed;
  record.bake = bake;
  record.inputs = std::move(key.inputs);
  record.build = bake_build_identity();
  record.asset_bytes = bytes.size();
  record.asset_hash = content_hash(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  // The record first: a reader that finds the .glb finds its record (each write is atomic).
  std::string json = record_json(record);
  write_file_atomic(record_path(out.file), std::span(reinterpret_cast<const uint8_t*>(json.data()), json.size()));
  write_file_atomic(out.file, bytes);
  // Render from the stored asset on a miss too, so a hit gives the very same image.
  out.model = load_glb(out.file);
  return out;
}

SpeciesSource cached_species_source(const SpeciesCacheOptions& options, SpeciesCacheCounts* counts) {
  return [options, counts](const SpeciesDesc& s, const BakeDesc& bake) {
    std::filesystem::path dir = options.dir.empty() ? default_cache_dir() : options.dir;
    std::function<void(double)> progress;
    if (options.progress) progress = [&](double f) { options.progress(s, f); };
    CachedSpecies c = load_or_bake_species(s, bake, dir, options.ctx, progress);
    if (counts) (c.hit ? counts->hits : counts->misses)++;
    if (options.log) {
      char line[512];
      if (c.hit)
        std::snprintf(line, sizeof(line), "species %s: cached %s", s.preset.filename().c_str(), c.file.c_str());
      else
        std::snprintf(line, sizeof(line), "species %s: generated in %.1f s, baked in %.1f s -> %s",
                      s.preset.filename().c_str(), c.generate_seconds, c.bake_seconds, c.file.c_str());
      options.log(line);
    }
    return std::move(c.model);
  };
}

}  // namespace forest
