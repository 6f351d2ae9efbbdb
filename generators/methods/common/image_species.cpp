#include "generators/methods/common/image_species.h"

#include <filesystem>
#include <memory>

#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/common/image_tree_util.h"
#include "generators/tree/pipe_model.h"

namespace forest {

ViewSet read_image_input(const TomlTable& t) {
  if (t.has("views") == t.has("crown"))
    t.fail(t.has("views") ? "crown" : "views", "give exactly one of `views` (a views.json file) or `crown` (synthetic)");
  if (auto crown = t.table("crown")) return synthesize_view_set(read_crown_spec(*crown));
  std::string rel = t.string("views");
  std::filesystem::path base = std::filesystem::path(t.file()).parent_path();
  std::filesystem::path file = base / rel;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) t.fail("views", "file not found: " + file.string());
  return load_view_set(file);
}

ImageTreeStyle read_image_tree_style(const TomlTable& t, const ImageTreeStyle& d) {
  ImageTreeStyle s = d;
  s.tip_radius = float(t.number("tip_radius", d.tip_radius, 1e-5, 1.0));
  s.pipe_exponent = float(t.number("pipe_exponent", d.pipe_exponent, 1.0, 4.0));
  return s;
}

Skeleton finish_image_tree(TreeGraph graph, const ImageTreeStyle& style, const ViewSet& views,
                           nlohmann::json stats) {
  assign_pipe_radii(graph, style.tip_radius, style.pipe_exponent);
  Skeleton out{std::move(graph)};
  // The crown is where the photographs show it: foliage outside any mask is dropped.
  auto shared_views = std::make_shared<const ViewSet>(views);
  out.keep_leaves = [shared_views](TreeGraph& g) { drop_leaves_outside_masks(g, *shared_views); };
  out.meta["method_stats"] = std::move(stats);
  return out;
}

}  // namespace forest
