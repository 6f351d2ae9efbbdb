#include <cstdio>

#include "engine/app/app_common.h"
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
  options.common_scale = !args.own_scale;
  CommandContext context(context_options(args.device, false));
  std::vector<GalleryEntry> entries;
  FrameImage sheet;
  {
    ProgressBar bar("gallery");
    sheet = render_gallery(context.ctx, presets, options, &entries,
                           [&](size_t done, size_t total) { bar.update(double(done) / double(total)); });
  }
  if (validation_failed(context.ctx, "image")) return 1;
  write_image(sheet, args.out);
  std::printf("%-24s %-14s %10s %8s %8s\n", "preset", "method", "triangles", "leaves", "height");
  for (const GalleryEntry& e : entries)
    std::printf("%-24s %-14s %10zu %8zu %7.1fm\n", e.name.c_str(), e.method.c_str(), e.triangles, e.leaves, e.height);
  std::printf("wrote %s: %zu presets, %u x %u pixels\n", args.out.c_str(), entries.size(), sheet.width, sheet.height);
  return 0;
}

}  // namespace forest::app
