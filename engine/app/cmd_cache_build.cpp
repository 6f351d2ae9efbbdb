// forest cache build: bakes species into the cache ahead of time. The work list (presets
// given, or a scene's [[species]] with its [bake]) is made unique by cache key and sorted by
// it, so every machine computes the same list; --shard i/n takes every n-th spec from the
// i-th, and --jobs N bakes that many at once, each on its own Vulkan context. A spec already
// cached is a hit and costs nothing, so shards and reruns can overlap freely.
#include <algorithm>
#include <atomic>
#include <exception>
#include <cstdio>
#include <mutex>
#include <thread>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/scene/scene_file.h"
#include "engine/tools/bake/species_cache.h"
#include "generators/bake/priority/priority.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

namespace fs = std::filesystem;

struct BuildSpec {
  SpeciesDesc species;
  BakeDesc bake;
  std::string key;
};

struct Shard {
  uint32_t index = 0, count = 1;
};

Shard parse_shard(const std::string& text) {
  Shard s;
  if (text.empty()) return s;
  unsigned i = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%u/%u%c", &i, &n, &tail) != 2 || n == 0 || i >= n || n > 100000)
    throw InputError("--shard", 0, "", "'" + text + "' is not i/n with 0 <= i < n (e.g. 0/4)");
  s.index = i;
  s.count = n;
  return s;
}

// The specs asked for, each once, sorted by key.
std::vector<BuildSpec> build_specs(const CacheArgs& a) {
  std::vector<BuildSpec> specs;
  BakeDesc preset_bake;
  if (a.priority) preset_bake.priority = *a.priority;
  if (a.views) preset_bake.views = *a.views;
  if (a.resolution) preset_bake.resolution = *a.resolution;
  if (a.no_impostor) preset_bake.impostor = false;
  if (!parse_priority(preset_bake.priority))
    throw InputError("--priority", 0, "", "unknown priority '" + preset_bake.priority +
                                              "' (random, density, orientation, combined, layered)");
  for (const std::string& p : a.presets) {
    BuildSpec s;
    s.species.preset = p;
    s.bake = preset_bake;
    specs.push_back(std::move(s));
  }
  if (!a.scene.empty()) {
    SceneDesc desc = load_scene_file(a.scene);
    for (const SpeciesDesc& sp : desc.species)
      if (!sp.preset.empty()) specs.push_back({sp, desc.bake, ""});
  }
  if (specs.empty()) throw InputError("forest cache build", 0, "", "name presets or --scene SCENE");
  for (BuildSpec& s : specs) s.key = species_cache_key(s.species, s.bake);
  std::sort(specs.begin(), specs.end(), [](const BuildSpec& x, const BuildSpec& y) { return x.key < y.key; });
  specs.erase(std::unique(specs.begin(), specs.end(), [](const BuildSpec& x, const BuildSpec& y) { return x.key == y.key; }),
              specs.end());
  return specs;
}

struct BuildResults {
  std::mutex mutex;
  std::atomic<size_t> next{0};
  size_t done = 0, hits = 0;
  std::exception_ptr error;  // the first failure; the other workers stop taking work
  std::string validation;    // the last validation message, when the layer reported one
};

// One worker: its own context, specs taken from the shared counter until none are left.
void build_worker(const std::vector<const BuildSpec*>& work, const fs::path& dir, const CacheArgs& a,
                  BuildResults& results, ProgressBar& bar) {
  try {
    CommandContext context(context_options(a.device, a.validate));
    for (size_t i; (i = results.next++) < work.size();) {
      {
        std::lock_guard lock(results.mutex);
        if (results.error || !results.validation.empty()) return;
      }
      const BuildSpec& s = *work[i];
      CachedSpecies c = load_or_bake_species(s.species, s.bake, dir, &context.ctx);
      std::lock_guard lock(results.mutex);
      if (context.ctx.validation_messages > 0) {
        results.validation = context.ctx.last_validation_message;
        return;
      }
      results.done++;
      results.hits += c.hit;
      bar.finish();
      char line[1024];
      if (c.hit)
        std::snprintf(line, sizeof line, "cached  %s -> %s", s.species.preset.c_str(), c.file.filename().c_str());
      else
        std::snprintf(line, sizeof line, "baked   %s in %.1f s -> %s", s.species.preset.c_str(),
                      c.generate_seconds + c.bake_seconds, c.file.filename().c_str());
      print_line(line);
      bar.update(double(results.done) / double(work.size()));
    }
  } catch (...) {
    std::lock_guard lock(results.mutex);
    if (!results.error) results.error = std::current_exception();
  }
}

}  // namespace

int run_cache_build(const CacheArgs& a) {
  Shard shard = parse_shard(a.shard);
  std::vector<BuildSpec> specs = build_specs(a);
  std::vector<const BuildSpec*> work;
  for (size_t i = shard.index; i < specs.size(); i += shard.count) work.push_back(&specs[i]);
  fs::path dir = a.cache.empty() ? default_cache_dir() : fs::path(a.cache);
  std::printf("cache build: %zu of %zu specs (shard %u/%u), %u jobs, into %s\n", work.size(), specs.size(), shard.index,
              shard.count, a.jobs, dir.c_str());
  std::fflush(stdout);
  BuildResults results;
  ProgressBar bar("cache build");
  bar.update(0.0);
  std::vector<std::thread> workers;
  uint32_t jobs = std::max(1u, std::min<uint32_t>(a.jobs, uint32_t(work.size())));
  for (uint32_t j = 0; j < jobs; ++j)
    workers.emplace_back([&] { build_worker(work, dir, a, results, bar); });
  for (std::thread& t : workers) t.join();
  bar.finish();
  if (!results.validation.empty()) {
    std::fprintf(stderr, "forest: Vulkan validation message during cache build: %s\n", results.validation.c_str());
    return 1;
  }
  // main() turns it into one line and its exit code (2 for a bad preset, 1 for the device).
  if (results.error) std::rethrow_exception(results.error);
  std::printf("cache build: %zu specs, %zu baked, %zu already cached\n", results.done, results.done - results.hits,
              results.hits);
  return 0;
}

}  // namespace forest::app
