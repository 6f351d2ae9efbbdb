// What several subcommands share: a Vulkan context that lives exactly as long as the
// command, the validation verdict before anything is written, scenes built from the
// species cache, and text files written atomically.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "engine/scene/scene.h"
#include "engine/vk/context.h"

namespace forest::app {

// --device and --validate (or FOREST_VALIDATION=1) as context options.
vk::ContextOptions context_options(const std::string& device, bool validate);

// A command's Vulkan context: created by the constructor, destroyed when the command is
// done, also when it throws, so no path leaks a device. destroy() may come earlier (walk
// tears down before its verdict); destroying again is harmless, as destroy_context skips
// handles that are null.
class CommandContext {
 public:
  explicit CommandContext(const vk::ContextOptions& options);
  ~CommandContext();
  CommandContext(const CommandContext&) = delete;
  CommandContext& operator=(const CommandContext&) = delete;
  void destroy();
  vk::Context ctx;
};

// True when the validation layer reported anything: the command then writes nothing and
// exits 1. Prints "forest: N Vulkan validation message(s); no <unwritten> written", with
// the last message when `name_last`.
bool validation_failed(const vk::Context& ctx, const char* unwritten, bool name_last = false);

// One line to stdout, flushed: progress of the species cache must show before a long bake.
void print_line(const std::string& line);

// --width / --height over the scene file's [render] size.
void override_size(SceneDesc& desc, std::optional<uint32_t> width, std::optional<uint32_t> height);

// The scene with its preset species from the cache (generated and baked on first use, then
// loaded), as `forest render` and `forest walk` draw it; warns on stderr when placement
// found room for fewer trees than asked. `cache_dir` empty: default_cache_dir().
Scene build_cached_scene(const SceneDesc& desc, const std::string& scene_file, const std::string& cache_dir);

// `text` to `path` through a temporary file and a rename: readers never see half a file.
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace forest::app
