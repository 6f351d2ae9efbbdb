#include "engine/app/app_common.h"

#include <cstdio>
#include <memory>
#include <span>

#include "engine/app/progress.h"
#include "engine/tools/bake/species_cache.h"
#include "generators/asset/asset_io.h"

namespace forest::app {

vk::ContextOptions context_options(const std::string& device, bool validate) {
  vk::ContextOptions options;
  options.device = device;
  options.validation = validate || vk::validation_from_env();
  return options;
}

CommandContext::CommandContext(const vk::ContextOptions& options) {
  // A constructor that throws runs no destructor: what creation made so far goes here.
  try {
    vk::create_context(ctx, options);
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
}

CommandContext::~CommandContext() { vk::destroy_context(ctx); }

void CommandContext::destroy() { vk::destroy_context(ctx); }

bool validation_failed(const vk::Context& ctx, const char* unwritten, bool name_last) {
  if (ctx.validation_messages == 0) return false;
  if (name_last)
    std::fprintf(stderr, "forest: %u Vulkan validation message(s); no %s written (last: %s)\n",
                 ctx.validation_messages.load(), unwritten, ctx.last_validation_message.c_str());
  else
    std::fprintf(stderr, "forest: %u Vulkan validation message(s); no %s written\n", ctx.validation_messages.load(),
                 unwritten);
  return true;
}

void print_line(const std::string& line) { std::printf("%s\n", line.c_str()), std::fflush(stdout); }

void override_size(SceneDesc& desc, std::optional<uint32_t> width, std::optional<uint32_t> height) {
  if (width) desc.width = *width;
  if (height) desc.height = *height;
}

Scene build_cached_scene(const SceneDesc& desc, const std::string& scene_file, const std::string& cache_dir) {
  SpeciesCacheOptions cache;
  cache.dir = cache_dir;
  // A bake on a cache miss takes 20-60 s a species: a bar while it runs (terminals only).
  auto bar = std::make_shared<ProgressBar>("");
  cache.log = [bar](const std::string& line) {
    bar->finish();
    print_line(line);
  };
  cache.progress = [bar](const SpeciesDesc& s, double f) {
    bar->relabel("baking " + s.preset.filename().string());
    bar->update(f);
  };
  SceneBuildOptions build;
  build.species = cached_species_source(cache);
  Scene scene = build_scene(desc, build);
  if (scene.placement_shortfall > 0)
    std::fprintf(stderr, "forest: %s: placement: only %u of %u trees found room (min_spacing / radius / max_slope)\n",
                 scene_file.c_str(), desc.placement.count - scene.placement_shortfall, desc.placement.count);
  return scene;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace forest::app
