// forest: offline tree generators and the real-time forest renderer, one executable.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "engine/app/commands.h"
#include "engine/vk/context.h"
#include "generators/core/input_error.h"

using namespace forest;

int main(int argc, char** argv) {
  CLI::App cli{"forest: tree generators and a GPU-pruned forest renderer (Vulkan 1.3)"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "forest 0.1.0");

  app::InfoArgs info;
  auto* info_cmd = cli.add_subcommand("info", "List Vulkan devices, pick one and check the features the engine relies on");
  info_cmd->add_option("--device", info.device, "Device index or name substring (default: $FOREST_DEVICE, then discrete GPU first)");

  app::GenerateArgs gen;
  uint64_t gen_seed = 0;
  auto* gen_cmd = cli.add_subcommand("generate", "Generate a tree model from a species preset and write a .glb asset");
  gen_cmd->add_option("--species", gen.species, "Species preset (TOML)")->check(CLI::ExistingFile);
  gen_cmd->add_option("--method", gen.method, "Modeling method id (uses its built-in preset without --species)");
  auto* seed_opt = gen_cmd->add_option("--seed", gen_seed, "Random seed (overrides the preset's)");
  gen_cmd->add_option("--out", gen.out, "Output .glb");
  gen_cmd->add_option("--svg", gen.svg, "Also write the 2D curves as SVG (method magnetic, mode 2d)");

  app::MakeInputsArgs inputs;
  auto* inputs_cmd = cli.add_subcommand("make-inputs", "Write synthetic inputs (masks, poses, strokes, samples) for every method");
  inputs_cmd->add_option("--out", inputs.out, "Output folder (one subfolder per method)")->required();

  app::LearnArgs learn;
  uint64_t learn_seed = 0;
  size_t learn_trees = 0;
  auto* learn_cmd = cli.add_subcommand("learn", "Learn plantons and transitions from sample trees (method plantons) into a model file");
  learn_cmd->add_option("--out", learn.out, "Output model (.json)")->required();
  auto* learn_seed_opt = learn_cmd->add_option("--seed", learn_seed, "Seed of k-means and of the sample trees (default 1)");
  learn_cmd->add_option("--species", learn.species, "Sample trees from these species presets (any method)")->check(CLI::ExistingFile);
  learn_cmd->add_option("--samples", learn.samples, "Sample file (JSON trees, see forest make-inputs)")->check(CLI::ExistingFile);
  learn_cmd->add_flag("--ground-truth", learn.ground_truth, "Sample trees from the synthetic ground truth (plantons T, P, S, L)");
  auto* learn_trees_opt = learn_cmd->add_option("--trees", learn_trees, "Trees per species, or ground-truth trees")->check(CLI::Range(1, 64));
  learn_cmd->add_option("--stem-plantons", learn.stem_plantons, "k-means k for stems")->check(CLI::Range(1, 500));
  learn_cmd->add_option("--leaf-plantons", learn.leaf_plantons, "k-means k for leaves")->check(CLI::Range(1, 500));
  learn_cmd->add_option("--e-max", learn.e_max, "Organs farther than this from their planton start a new one")->check(CLI::Range(0.01, 1e6));

  app::PreviewArgs preview;
  auto* preview_cmd = cli.add_subcommand("preview", "Render a turntable contact sheet of a .glb model");
  preview_cmd->add_option("model", preview.model, "Model (.glb)")->required();
  preview_cmd->add_option("--out", preview.out, "Output image (.png)")->required();
  preview_cmd->add_option("--size", preview.size, "Pixels per view")->check(CLI::Range(32, 4096));
  preview_cmd->add_option("--views", preview.views, "Number of views around the model")->check(CLI::Range(1, 64));
  preview_cmd->add_option("--device", preview.device, "Device index or name substring");

  app::GalleryArgs gallery;
  auto* gallery_cmd = cli.add_subcommand("gallery", "Render every species preset into one labelled contact sheet");
  gallery_cmd->add_option("--out", gallery.out, "Output image (.png)")->required();
  gallery_cmd->add_option("--species-dir", gallery.species_dir, "Folder of species presets (default: scenes/species)");
  gallery_cmd->add_option("--size", gallery.size, "Pixels per preset")->check(CLI::Range(32, 2048));
  gallery_cmd->add_option("--columns", gallery.columns, "Presets per row (default: about square)")->check(CLI::Range(1, 64));
  gallery_cmd->add_option("--device", gallery.device, "Device index or name substring");

  app::BakeArgs bake;
  uint64_t bake_seed = 0;
  auto* bake_cmd = cli.add_subcommand("bake", "Add the metaball hull, priority-sorted leaves and PR-measured lambda/scale tables to a model");
  bake_cmd->add_option("model", bake.model, "Model (.glb)")->required();
  bake_cmd->add_option("--out", bake.out, "Baked model (default: in place)");
  bake_cmd->add_option("--priority", bake.priority, "Leaf order: random, density, orientation, combined, layered");
  auto* bake_seed_opt = bake_cmd->add_option("--seed", bake_seed, "Seed of the random parts (default: the model's)");
  bake_cmd->add_option("--views", bake.views, "Views averaged by the PR measurement")->check(CLI::Range(1, 64));
  bake_cmd->add_option("--resolution", bake.resolution, "Pixels of each coverage render")->check(CLI::Range(32, 4096));
  bake_cmd->add_option("--device", bake.device, "Device index or name substring");

  app::ReportArgs report;
  auto* report_cmd = cli.add_subcommand("report", "Plot a baked model's PR diagram, s(lambda) and lambda(d) as PNG + CSV");
  report_cmd->add_option("model", report.model, "Baked model (.glb)")->required();
  report_cmd->add_option("--out", report.out, "Output folder")->required();

  app::RenderArgs render;
  uint32_t width = 0, height = 0;
  auto* render_cmd = cli.add_subcommand("render", "Render a scene headless to an image");
  render_cmd->add_option("scene", render.scene, "Scene file (TOML)")->required();
  render_cmd->add_option("--out", render.out, "Output image (.png)")->required();
  render_cmd->add_option("--device", render.device, "Device index or name substring");
  auto* width_opt = render_cmd->add_option("--width", width, "Override [render].width")->check(CLI::Range(16, 8192));
  auto* height_opt = render_cmd->add_option("--height", height, "Override [render].height")->check(CLI::Range(16, 8192));
  std::string occlusion;
  auto* occlusion_opt = render_cmd->add_option("--occlusion", occlusion,
                                               "Depth-buffer occlusion feedback (overrides [render].occlusion)")
                            ->check(CLI::IsMember({"on", "off"}));
  render_cmd->add_option("--mode", render.mode, "Prune mode (overrides [render].mode)")
      ->check(CLI::IsMember({"full", "cook", "opt"}));
  render_cmd->add_option("--view", render.view, "shaded, lambda (trees by detail level) or mask (coverage for forest compare)")
      ->check(CLI::IsMember({"shaded", "lambda", "mask"}));
  render_cmd->add_flag("--stats", render.stats, "Print GPU statistics and timings");
  uint32_t render_frame = 0;
  double render_time = 0.0;
  render_cmd->add_option("--path", render.path, "Camera path ([[path]] name) to take the camera from");
  auto* frame_opt = render_cmd->add_option("--frame", render_frame, "Frame of --path (time = frame / fps)");
  auto* time_opt = render_cmd->add_option("--time", render_time, "Seconds along --path")->check(CLI::Range(0.0, 1e6));
  frame_opt->excludes(time_opt);
  render_cmd->add_option("--cache", render.cache, "Species cache folder (default: $FOREST_CACHE or ~/.cache/forest)");
  render_cmd->add_flag("--validate", render.validate,
                       "Enable the Khronos validation layer; any warning or error fails (also FOREST_VALIDATION=1)");

  app::CompareArgs compare;
  double min_quality = 0;
  auto* compare_cmd = cli.add_subcommand("compare", "Precision, Recall and Q of a coverage image against a reference, with a tp/fp/fn picture");
  compare_cmd->add_option("reference", compare.reference, "Reference coverage image (full detail)")->required()->check(CLI::ExistingFile);
  compare_cmd->add_option("test", compare.test, "Test coverage image (pruned)")->required()->check(CLI::ExistingFile);
  compare_cmd->add_option("--diff", compare.diff, "Write the Fig 7.1 picture: tp light green, fp red, fn dark green");
  compare_cmd->add_option("--threshold", compare.threshold, "A pixel is covered from this value of its brightest channel")->check(CLI::Range(1, 255));
  auto* min_quality_opt = compare_cmd->add_option("--min-quality", min_quality, "Exit 3 when Q is below this")->check(CLI::Range(0.0, 1.0));
  app::WalkArgs walk;
  uint32_t walk_width = 0, walk_height = 0, walk_frames = 0, walk_resize_at = 0;
  auto* walk_cmd = cli.add_subcommand("walk", "Walk through a scene in a window (fly camera, HUD, prune modes)");
  walk_cmd->add_option("scene", walk.scene, "Scene file (TOML)")->required();
  walk_cmd->add_option("--device", walk.device, "Device index or name substring");
  auto* walk_width_opt = walk_cmd->add_option("--width", walk_width, "Override [render].width")->check(CLI::Range(16, 8192));
  auto* walk_height_opt = walk_cmd->add_option("--height", walk_height, "Override [render].height")->check(CLI::Range(16, 8192));
  auto* walk_frames_opt = walk_cmd->add_option("--frames", walk_frames, "Quit after N frames (scripted run, fixed 1/30 s steps)")
                              ->check(CLI::Range(1, 1000000));
  walk_cmd->add_option("--screenshot", walk.screenshot, "PNG of the last frame with --frames; else where [C] writes");
  walk_cmd->add_flag("--fly", walk.fly, "Scripted camera move: fly forward while turning");
  walk_cmd->add_flag("--play", walk.play, "Start playing the scene's camera path (as if [P] was pressed)");
  auto* walk_resize_opt = walk_cmd->add_option("--resize-at", walk_resize_at, "Scripted: resize the window at this frame")
                              ->check(CLI::Range(0, 1000000));
  walk_cmd->add_flag("--no-hud", walk.no_hud, "Start with the HUD hidden ([H] toggles)");
  walk_cmd->add_option("--present", walk.present, "Copy to the window by blit, or by a shader pass (auto: blit where supported)")
      ->check(CLI::IsMember({"auto", "blit", "pass"}));
  walk_cmd->add_flag("--validate", walk.validate,
                     "Enable the Khronos validation layer; any warning or error fails (also FOREST_VALIDATION=1)");

  app::BenchArgs bench;
  uint32_t bench_width = 0, bench_height = 0;
  auto* bench_cmd = cli.add_subcommand("bench", "Play a scene's camera path in several prune modes: per-frame CSV, JSON summary vs Cook, plots");
  bench_cmd->add_option("scene", bench.scene, "Scene file (TOML) with a [[path]]")->required();
  bench_cmd->add_option("--path", bench.path, "Camera path name (default: the first [[path]])");
  bench_cmd->add_option("--modes", bench.modes, "Comma-separated: full, cook, opt, opt-combined, opt-occl");
  auto* bench_frames_opt = bench_cmd->add_option("--frames", bench.frames, "At most N frames")->check(CLI::Range(1, 1000000));
  auto* bench_every_opt = bench_cmd->add_option("--every", bench.every, "Play every k-th frame of the path")->check(CLI::Range(1, 1000000));
  bench_frames_opt->excludes(bench_every_opt);
  bench_cmd->add_option("--pr-every", bench.pr_every, "P, R, Q vs full detail at every k-th played frame (0: never)")->check(CLI::Range(0, 1000000));
  bench_cmd->add_option("--occlusion-warmup", bench.occlusion_warmup,
                        "Occlusion modes: path frames drawn (unrecorded) before each played one (default: all in between)")
      ->check(CLI::Range(0, 1000000));
  auto* bench_width_opt = bench_cmd->add_option("--width", bench_width, "Override [render].width")->check(CLI::Range(16, 8192));
  auto* bench_height_opt = bench_cmd->add_option("--height", bench_height, "Override [render].height")->check(CLI::Range(16, 8192));
  bench_cmd->add_option("--probe-instances", bench.probe_instances, "Throughput probe: sheets of 18 432 triangles drawn (0: no probe)")->check(CLI::Range(0, 4096));
  bench_cmd->add_option("--out", bench.out, "Output folder (must exist)")->required();
  bench_cmd->add_option("--device", bench.device, "Device index or name substring");
  bench_cmd->add_option("--cache", bench.cache, "Species cache folder (default: $FOREST_CACHE or ~/.cache/forest)");
  bench_cmd->add_flag("--validate", bench.validate, "Enable the Khronos validation layer (also FOREST_VALIDATION=1)");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, exit code 2, as for every other bad input.
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "forest: %s (see forest --help)\n", msg.c_str());
    return 2;
  }

  try {
    if (*info_cmd) return app::run_info(info);
    if (*gen_cmd) {
      if (*seed_opt) gen.seed = gen_seed;
      return app::run_generate(gen);
    }
    if (*inputs_cmd) return app::run_make_inputs(inputs);
    if (*learn_cmd) {
      if (*learn_seed_opt) learn.seed = learn_seed;
      if (*learn_trees_opt) learn.trees = learn_trees;
      return app::run_learn(learn);
    }
    if (*preview_cmd) return app::run_preview(preview);
    if (*gallery_cmd) return app::run_gallery(gallery);
    if (*bake_cmd) {
      if (*bake_seed_opt) bake.seed = bake_seed;
      return app::run_bake(bake);
    }
    if (*report_cmd) return app::run_report(report);
    if (*compare_cmd) {
      if (*min_quality_opt) compare.min_quality = min_quality;
      return app::run_compare(compare);
    }
    if (*render_cmd) {
      if (*width_opt) render.width = width;
      if (*height_opt) render.height = height;
      if (*occlusion_opt) render.occlusion = occlusion == "on";
      if (*frame_opt) render.frame = render_frame;
      if (*time_opt) render.time = render_time;
      return app::run_render(render);
    }
    if (*bench_cmd) {
      if (*bench_width_opt) bench.width = bench_width;
      if (*bench_height_opt) bench.height = bench_height;
      return app::run_bench(bench);
    }
    if (*walk_cmd) {
      if (*walk_width_opt) walk.width = walk_width;
      if (*walk_height_opt) walk.height = walk_height;
      if (*walk_frames_opt) walk.frames = walk_frames;
      if (*walk_resize_opt) walk.resize_at = walk_resize_at;
      return app::run_walk(walk);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "forest: %s\n", e.what());
    return 2;
  } catch (const vk::VkFailure& e) {
    std::fprintf(stderr, "forest: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "forest: internal error: %s\n", e.what());
    return 1;
  }
  return 2;
}
