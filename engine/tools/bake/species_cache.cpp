#include "engine/tools/bake/species_cache.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "engine/tools/bake/tree_bake.h"
#include "engine/vk/context.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"

namespace forest {

namespace {

// FNV-1a 64 over the bytes, run twice with different offsets: a 128-bit content key (not
// cryptographic; collisions between honest specs are what matters).
struct ContentHash {
  uint64_t a = 0xcbf29ce484222325ull, b = 0x84222325cbf29ce4ull;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) {
      a = (a ^ c) * 0x100000001b3ull;
      b = (b ^ c) * 0x100000001b3ull;
      b ^= b >> 29;
    }
    // Length-prefix-free framing: a separator after every field.
    a = (a ^ 0xff) * 0x100000001b3ull;
    b = (b ^ 0xfe) * 0x100000001b3ull;
  }
  std::string hex() const {
    char s[33];
    std::snprintf(s, sizeof(s), "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
    return s;
  }
};

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", "cannot read species preset");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::filesystem::path default_cache_dir() {
  if (const char* c = std::getenv("FOREST_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "forest";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "forest";
  return ".forest-cache";
}

std::string species_cache_key(const SpeciesDesc& species, const BakeDesc& bake) {
  ContentHash h;
  h.add("forest species cache v" + std::to_string(kSpeciesCacheVersion));
  h.add(read_text(species.preset));
  h.add(species.seed ? "seed " + std::to_string(*species.seed) : "preset seed");
  h.add("bake " + bake.priority + " " + std::to_string(bake.views) + " " + std::to_string(bake.resolution) +
        (bake.impostor ? "" : " no impostor"));
  return h.hex();
}

CachedSpecies load_or_bake_species(const SpeciesDesc& species, const BakeDesc& bake,
                                   const std::filesystem::path& cache_dir, vk::Context* ctx) {
  CachedSpecies out;
  out.file = cache_dir / (species.preset.stem().string() + "-" + species_cache_key(species, bake) + ".glb");
  std::error_code ec;
  if (std::filesystem::is_regular_file(out.file, ec)) {
    try {
      out.model = load_glb(out.file);
      out.hit = true;
      return out;
    } catch (const InputError&) {
      // A damaged cache entry (disk full, killed writer on a filesystem without atomic
      // rename): rebuild it below.
    }
  }
  std::filesystem::create_directories(cache_dir, ec);
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
  if (ctx) {
    bake_tree_model(*ctx, out.model, settings);
  } else {
    vk::Context own;
    vk::ContextOptions o;
    o.validation = vk::validation_from_env();
    try {
      vk::create_context(own, o);
      bake_tree_model(own, out.model, settings);
    } catch (...) {
      vk::destroy_context(own);
      throw;
    }
    vk::destroy_context(own);
  }
  out.generate_seconds = std::chrono::duration<double>(t1 - t0).count();
  out.bake_seconds = std::chrono::duration<double>(clock::now() - t1).count();
  save_glb(out.model, out.file);  // temporary file + rename
  // Render from the stored asset on a miss too, so a hit gives the very same image.
  out.model = load_glb(out.file);
  return out;
}

SpeciesSource cached_species_source(const SpeciesCacheOptions& options, SpeciesCacheCounts* counts) {
  return [options, counts](const SpeciesDesc& s, const BakeDesc& bake) {
    std::filesystem::path dir = options.dir.empty() ? default_cache_dir() : options.dir;
    CachedSpecies c = load_or_bake_species(s, bake, dir, options.ctx);
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
