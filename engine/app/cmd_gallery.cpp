#include <cstdio>

#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/tools/gallery/gallery.h"
#include "engine/present/image_io.h"

namespace forest::app {

int run_gallery(const GalleryArgs& args) {
  check_output_path(args.out, "--out");
  std::vector<std::filesystem::path> presets = list_species_presets(args.species_dir);
  GalleryOptions options;
  options.size = args.size;
  options.columns = args.columns;
  vk::Context ctx;
  vk::ContextOptions ctx_options;
  ctx_options.device = args.device;
  ctx_options.validation = vk::validation_from_env();
  int code = 0;
  try {
    vk::create_context(ctx, ctx_options);
    std::vector<GalleryEntry> entries;
    FrameImage sheet;
    {
      ProgressBar bar("gallery");
      sheet = render_gallery(ctx, presets, options, &entries,
                             [&](size_t done, size_t total) { bar.update(double(done) / double(total)); });
    }
    if (ctx.validation_messages > 0) {
      std::fprintf(stderr, "forest: %u Vulkan validation message(s); no image written\n", ctx.validation_messages.load());
      code = 1;
    } else {
      write_image(sheet, args.out);
      std::printf("%-24s %-14s %10s %8s %8s\n", "preset", "method", "triangles", "leaves", "height");
      for (const GalleryEntry& e : entries)
        std::printf("%-24s %-14s %10zu %8zu %7.1fm\n", e.name.c_str(), e.method.c_str(), e.triangles, e.leaves, e.height);
      std::printf("wrote %s: %zu presets, %u x %u pixels\n", args.out.c_str(), entries.size(), sheet.width, sheet.height);
    }
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  return code;
}

}  // namespace forest::app
