// forest: offline tree generators and the real-time forest renderer, one executable.
#include <map>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/app/commands.h"
#include "generators/core/limits.h"
#include "engine/vk/context.h"
#include "generators/core/input_error.h"

using namespace forest;

namespace {

// One subcommand: its CLI11 node, and what runs when the command line chose it. The
// arguments CLI11 parses into are shared with the `run` closure, so they outlive the parse.
struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

constexpr const char* kDeviceHelp = "Device index or name substring";
constexpr const char* kCacheHelp = "Species cache folder (default: $FOREST_CACHE or ~/.cache/forest)";
constexpr const char* kValidateHelp =
    "Enable the Khronos validation layer; any warning or error fails (also FOREST_VALIDATION=1)";

// --width / --height over the scene's [render] size (render, walk, bench).
void add_size_options(CLI::App* cmd, std::optional<uint32_t>& width, std::optional<uint32_t>& height) {
  cmd->add_option("--width", width, "Override [render].width")->check(CLI::Range(kMinFrameSide, kMaxFrameSide));
  cmd->add_option("--height", height, "Override [render].height")->check(CLI::Range(kMinFrameSide, kMaxFrameSide));
}

// A subcommand whose options CLI11 parses straight into `args`, run with them once parsed.
template <typename Args>
Command command(CLI::App* cmd, std::shared_ptr<Args> args, int (*run)(const Args&)) {
  return {cmd, [args, run] { return run(*args); }};
}

Command add_info(CLI::App& cli) {
  auto args = std::make_shared<app::InfoArgs>();
  auto* cmd = cli.add_subcommand("info", "List Vulkan devices, pick one and check the features the engine relies on");
  cmd->add_option("--device", args->device, "Device index or name substring (default: $FOREST_DEVICE, then discrete GPU first)");
  return command(cmd, args, app::run_info);
}

Command add_generate(CLI::App& cli) {
  auto args = std::make_shared<app::GenerateArgs>();
  auto* cmd = cli.add_subcommand("generate", "Generate a tree model from a species preset and write a .glb asset");
  cmd->add_option("--species", args->species, "Species preset (TOML)")->check(CLI::ExistingFile);
  cmd->add_option("--method", args->method, "Modeling method id (uses its built-in preset without --species)");
  cmd->add_option("--seed", args->seed, "Random seed (overrides the preset's)");
  cmd->add_option("--out", args->out, "Output .glb");
  cmd->add_option("--svg", args->svg, "Also write the 2D curves as SVG (method magnetic, mode 2d)");
  return command(cmd, args, app::run_generate);
}

Command add_make_inputs(CLI::App& cli) {
  auto args = std::make_shared<app::MakeInputsArgs>();
  auto* cmd = cli.add_subcommand("make-inputs", "Write synthetic inputs (masks, poses, strokes, samples) for every method");
  cmd->add_option("--out", args->out, "Output folder (one subfolder per method)")->required();
  return command(cmd, args, app::run_make_inputs);
}

Command add_learn(CLI::App& cli) {
  auto args = std::make_shared<app::LearnArgs>();
  auto* cmd = cli.add_subcommand("learn", "Learn plantons and transitions from sample trees (method plantons) into a model file");
  cmd->add_option("--out", args->out, "Output model (.json)")->required();
  cmd->add_option("--seed", args->seed, "Seed of k-means and of the sample trees (default 1)");
  cmd->add_option("--species", args->species, "Sample trees from these species presets (any method)")->check(CLI::ExistingFile);
  cmd->add_option("--samples", args->samples, "Sample file (JSON trees, see forest make-inputs)")->check(CLI::ExistingFile);
  cmd->add_flag("--ground-truth", args->ground_truth, "Sample trees from the synthetic ground truth (plantons T, P, S, L)");
  cmd->add_option("--trees", args->trees, "Trees per species, or ground-truth trees")->check(CLI::Range(1, 64));
  cmd->add_option("--stem-plantons", args->stem_plantons, "k-means k for stems")->check(CLI::Range(1, 500));
  cmd->add_option("--leaf-plantons", args->leaf_plantons, "k-means k for leaves")->check(CLI::Range(1, 500));
  cmd->add_option("--e-max", args->e_max, "Organs farther than this from their planton start a new one")->check(CLI::Range(0.01, 1e6));
  return command(cmd, args, app::run_learn);
}

Command add_preview(CLI::App& cli) {
  auto args = std::make_shared<app::PreviewArgs>();
  auto* cmd = cli.add_subcommand("preview", "Render a turntable contact sheet of a .glb model");
  cmd->add_option("model", args->model, "Model (.glb)")->required();
  cmd->add_option("--out", args->out, "Output image (.png)")->required();
  cmd->add_option("--size", args->size, "Pixels per view")->check(CLI::Range(kMinBakeResolution, kMaxBakeResolution));
  cmd->add_option("--views", args->views, "Number of views around the model")->check(CLI::Range(1, 64));
  cmd->add_flag("--bark-lods", args->bark_lods,
                "One view per bark LOD level (LOD0 first), leaves hidden, in a row");
  cmd->add_flag("--impostor", args->impostor,
                "A second row: the model's baked impostor from the same views (its Q per size printed)");
  cmd->add_option("--device", args->device, kDeviceHelp);
  return command(cmd, args, app::run_preview);
}

Command add_gallery(CLI::App& cli) {
  auto args = std::make_shared<app::GalleryArgs>();
  auto* cmd = cli.add_subcommand("gallery", "Render every species preset into one labelled contact sheet");
  cmd->add_option("--out", args->out, "Output image (.png)")->required();
  cmd->add_option("--species-dir", args->species_dir, "Folder of species presets (default: scenes/species)");
  cmd->add_option("--size", args->size, "Pixels per preset")->check(CLI::Range(32, 2048));
  cmd->add_option("--columns", args->columns, "Presets per row (default: about square)")->check(CLI::Range(1, 64));
  cmd->add_flag("--own-scale", args->own_scale,
                "Frame each tree alone (default: one scale for all, beside a 1.8 m human figure)");
  cmd->add_option("--device", args->device, kDeviceHelp);
  return command(cmd, args, app::run_gallery);
}

Command add_bake(CLI::App& cli) {
  auto args = std::make_shared<app::BakeArgs>();
  auto* cmd = cli.add_subcommand("bake", "Add the metaball hull, priority-sorted leaves and PR-measured lambda/scale tables to a model");
  cmd->add_option("model", args->model, "Model (.glb)")->required();
  cmd->add_option("--out", args->out, "Baked model (default: in place)");
  cmd->add_option("--priority", args->priority, "Leaf order: random, density, orientation, combined, layered");
  cmd->add_option("--seed", args->seed, "Seed of the random parts (default: the model's)");
  cmd->add_option("--views", args->views, "Views averaged by the PR measurement")->check(CLI::Range(1, 64));
  cmd->add_option("--resolution", args->resolution,
                  "Largest projected size of the PR tables, pixels across the bounding sphere (the tables hold it and 5 halvings)")
      ->check(CLI::Range(kMinBakeResolution, kMaxPrSize0));
  cmd->add_option("--device", args->device, kDeviceHelp);
  return command(cmd, args, app::run_bake);
}

Command add_report(CLI::App& cli) {
  auto args = std::make_shared<app::ReportArgs>();
  auto* cmd = cli.add_subcommand("report", "Plot a baked model's PR diagram, s(lambda) and lambda(d) as PNG + CSV");
  cmd->add_option("model", args->model, "Baked model (.glb)")->required();
  cmd->add_option("--out", args->out, "Output folder")->required();
  return command(cmd, args, app::run_report);
}

Command add_measure(CLI::App& cli) {
  auto args = std::make_shared<app::MeasureArgs>();
  app::MeasureArgs& a = *args;
  auto* cmd = cli.add_subcommand("measure", "Habit, leaf coverage of 4 side views and leaf depth in the crown of one tree");
  auto* species = cmd->add_option("--species", a.species, "Species preset (TOML): all metrics")->check(CLI::ExistingFile);
  auto* model = cmd->add_option("--model", a.model, "Model (.glb): coverage and depth (no skeleton, no habit)")->check(CLI::ExistingFile);
  species->excludes(model);
  cmd->add_option("--seed", a.seed, "Random seed (overrides the preset's)");
  cmd->add_option("--json", a.json, "Also write the numbers as JSON");
  cmd->add_option("--masks", a.masks, "Existing folder: write the leaf masks (leaves_az<deg>.png)");
  cmd->add_option("--resolution", a.resolution, "Pixels of each square view")->check(CLI::Range(kMinBakeResolution, kMaxBakeResolution));
  cmd->add_option("--device", a.device, kDeviceHelp);
  cmd->add_flag("--validate", a.validate, kValidateHelp);
  return command(cmd, args, app::run_measure);
}

Command add_render(CLI::App& cli) {
  struct Parsed {
    app::RenderArgs args;
    std::string occlusion;  // on | off, into args.occlusion
    std::string shadows;    // on | off, into args.shadows
    std::string impostors;  // on | off, into args.impostors
    std::vector<float> sun;  // azimuth, elevation
  };
  auto p = std::make_shared<Parsed>();
  app::RenderArgs& a = p->args;
  auto* cmd = cli.add_subcommand("render", "Render a scene headless to an image");
  cmd->add_option("scene", a.scene, "Scene file (TOML)")->required();
  cmd->add_option("--out", a.out, "Output image (.png)")->required();
  cmd->add_option("--device", a.device, kDeviceHelp);
  add_size_options(cmd, a.width, a.height);
  auto* occlusion_opt = cmd->add_option("--occlusion", p->occlusion,
                                        "Depth-buffer occlusion feedback (overrides [render].occlusion)")
                            ->check(CLI::IsMember({"on", "off"}));
  auto* shadows_opt = cmd->add_option("--shadows", p->shadows, "Sun shadows, cascaded shadow maps (overrides [render].shadows)")
                          ->check(CLI::IsMember({"on", "off"}));
  auto* impostors_opt = cmd->add_option("--impostors", p->impostors, "Far trees as impostors where their baked Q allows (overrides [render].impostors)")
                            ->check(CLI::IsMember({"on", "off"}));
  auto* sun_opt = cmd->add_option("--sun", p->sun, "AZIMUTH,ELEVATION of the sun in degrees (azimuth from +x toward +z; overrides [sky].sun_direction)")
                      ->delimiter(',')->expected(2)->check(CLI::Range(-360.0, 360.0));
  cmd->add_option("--exposure", a.exposure, "Scene-linear multiplier before the tone map (overrides [render].exposure)")
      ->check(CLI::Range(1e-3, 1e3));
  cmd->add_option("--mode", a.mode, "Prune mode (overrides [render].mode)")
      ->check(CLI::IsMember(std::vector<std::string>(prune_mode_names().begin(), prune_mode_names().end())));
  cmd->add_option("--quality", a.quality, "PR quality Q every tree keeps in mode target (overrides [render].quality)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--view", a.view, "shaded, lambda (trees by detail level) or mask (coverage for forest compare)")
      ->check(CLI::IsMember({"shaded", "lambda", "mask"}));
  cmd->add_option("--overlay", a.overlay, "Debug overlay: pyramid (the depth pyramid occlusion tests against; needs occlusion on)")
      ->check(CLI::IsMember({"pyramid"}));
  cmd->add_flag("--stats", a.stats, "Print GPU statistics and timings");
  cmd->add_option("--path", a.path, "Camera path ([[path]] name) to take the camera from");
  auto* frame_opt = cmd->add_option("--frame", a.frame, "Frame of --path (time = frame / fps)");
  auto* time_opt = cmd->add_option("--time", a.time, "Seconds along --path")->check(CLI::Range(0.0, 1e6));
  frame_opt->excludes(time_opt);
  cmd->add_option("--cache", a.cache, kCacheHelp);
  cmd->add_flag("--validate", a.validate, kValidateHelp);
  return {cmd, [p, occlusion_opt, shadows_opt, impostors_opt, sun_opt] {
            if (*occlusion_opt) p->args.occlusion = p->occlusion == "on";
            if (*impostors_opt) p->args.impostors = p->impostors == "on";
            if (*shadows_opt) p->args.shadows = p->shadows == "on";
            if (*sun_opt) p->args.sun = glm::vec2(p->sun[0], p->sun[1]);
            return app::run_render(p->args);
          }};
}

Command add_compare(CLI::App& cli) {
  auto args = std::make_shared<app::CompareArgs>();
  auto* cmd = cli.add_subcommand("compare", "Precision, Recall and Q of a coverage image against a reference, with a tp/fp/fn picture");
  cmd->add_option("reference", args->reference, "Reference coverage image (full detail)")->required()->check(CLI::ExistingFile);
  cmd->add_option("test", args->test, "Test coverage image (pruned)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--diff", args->diff, "Write the Fig 7.1 picture: tp light green, fp red, fn dark green");
  cmd->add_option("--threshold", args->threshold, "A pixel is covered from this value of its brightest channel")->check(CLI::Range(1, 255));
  cmd->add_option("--min-quality", args->min_quality, "Exit 3 when Q is below this")->check(CLI::Range(0.0, 1.0));
  return command(cmd, args, app::run_compare);
}

Command add_walk(CLI::App& cli) {
  struct Parsed {
    app::WalkArgs args;
    std::string shadows;  // on | off, into args.shadows
    std::string impostors;  // on | off, into args.impostors
  };
  auto p = std::make_shared<Parsed>();
  app::WalkArgs& a = p->args;
  auto* cmd = cli.add_subcommand("walk", "Walk through a scene in a window (fly camera, HUD, prune modes)");
  cmd->add_option("scene", a.scene, "Scene file (TOML)")->required();
  cmd->add_option("--device", a.device, kDeviceHelp);
  add_size_options(cmd, a.width, a.height);
  cmd->add_option("--frames", a.frames, "Quit after N frames (scripted run, fixed 1/30 s steps)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--screenshot", a.screenshot, "PNG of the last frame with --frames; else where [C] writes");
  cmd->add_flag("--fly", a.fly, "Scripted camera move: fly forward while turning");
  cmd->add_flag("--play", a.play, "Start playing the scene's camera path (as if [P] was pressed)");
  cmd->add_option("--resize-at", a.resize_at, "Scripted: resize the window at this frame")->check(CLI::Range(0, 1000000));
  cmd->add_flag("--no-hud", a.no_hud, "Start with the HUD hidden ([H] toggles)");
  cmd->add_option("--present", a.present, "Copy to the window by blit, or by a shader pass (auto: blit where supported)")
      ->check(CLI::IsMember({"auto", "blit", "pass"}));
  auto* shadows_opt = cmd->add_option("--shadows", p->shadows, "Sun shadows (overrides [render].shadows; [J] toggles)")
                          ->check(CLI::IsMember({"on", "off"}));
  auto* impostors_opt = cmd->add_option("--impostors", p->impostors, "Far trees as impostors (overrides [render].impostors; [I] toggles)")
                            ->check(CLI::IsMember({"on", "off"}));
  cmd->add_flag("--validate", a.validate, kValidateHelp);
  return {cmd, [p, shadows_opt, impostors_opt] {
            if (*shadows_opt) p->args.shadows = p->shadows == "on";
            if (*impostors_opt) p->args.impostors = p->impostors == "on";
            return app::run_walk(p->args);
          }};
}

Command add_bench(CLI::App& cli) {
  auto args = std::make_shared<app::BenchArgs>();
  app::BenchArgs& a = *args;
  auto* cmd = cli.add_subcommand("bench", "Play a scene's camera path in several prune modes: per-frame CSV, JSON summary vs Cook, plots");
  cmd->add_option("scene", a.scene, "Scene file (TOML) with a [[path]]")->required();
  cmd->add_option("--path", a.path, "Camera path name (default: the first [[path]])");
  cmd->add_option("--modes", a.modes, "Comma-separated: full, cook, cook-random, opt, opt-<order> (random, density, orientation, combined, layered), opt-occl, opt-occl-instanced (leaves as card instances, not pulled), opt-occl-imp (with impostors), target");
  auto* frames_opt = cmd->add_option("--frames", a.frames, "At most N frames")->check(CLI::Range(1, 1000000));
  auto* every_opt = cmd->add_option("--every", a.every, "Play every k-th frame of the path")->check(CLI::Range(1, 1000000));
  frames_opt->excludes(every_opt);
  cmd->add_option("--pr-every", a.pr_every, "P, R, Q vs full detail at every k-th played frame (0: never)")->check(CLI::Range(0, 1000000));
  cmd->add_option("--tree-pr", a.tree_pr, "At PR frames, also Q of N trees in view, each drawn alone against its own full-detail mask")->check(CLI::Range(0, 10000));
  cmd->add_option("--occlusion-warmup", a.occlusion_warmup,
                  "Occlusion modes: path frames drawn (unrecorded) before each played one (default: all in between)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--shadows", a.shadows, "Sun shadows: on, off, or on,off (every mode played with each; default: [render].shadows)")
      ->check(CLI::IsMember({"on", "off", "on,off", "off,on"}));
  cmd->add_option("--impostors", a.impostors, "Far trees as impostors in every mode: on or off (default: [render].impostors; opt-occl-imp always)")
      ->transform(CLI::IsMember(std::map<std::string, bool>{{"on", true}, {"off", false}}));
  add_size_options(cmd, a.width, a.height);
  cmd->add_option("--probe-instances", a.probe_instances, "Throughput probe: sheets of 18 432 triangles drawn (0: no probe)")->check(CLI::Range(0u, kMaxProbeInstances));
  cmd->add_option("--out", a.out, "Output folder (made when missing)")->required();
  cmd->add_option("--device", a.device, kDeviceHelp);
  cmd->add_option("--cache", a.cache, kCacheHelp);
  cmd->add_flag("--validate", a.validate, "Enable the Khronos validation layer (also FOREST_VALIDATION=1)");
  return command(cmd, args, app::run_bench);
}

Command add_export(CLI::App& cli) {
  auto args = std::make_shared<app::ExportArgs>();
  auto* cmd = cli.add_subcommand("export", "Write a model for other clients (Blender, three.js, Godot): one .glb per LOD, no engine data");
  cmd->add_option("model", args->model, "Model (.glb)")->required();
  cmd->add_option("--out", args->out, "X.glb (LOD0); X_LOD1.glb ... beside it")->required();
  cmd->add_flag("--flatten", args->flatten, "Leaves as one mesh with COLOR_0, for clients without EXT_mesh_gpu_instancing");
  return command(cmd, args, app::run_export);
}

// forest cache ls | verify | clear | build: one subcommand with four of its own.
Command add_cache(CLI::App& cli) {
  auto a = std::make_shared<app::CacheArgs>();
  auto* cmd = cli.add_subcommand("cache", "The species cache: list, verify, clear or fill (in parallel, in shards) its entries");
  cmd->require_subcommand(1);
  cmd->add_option("--cache", a->cache, kCacheHelp);
  auto* ls = cmd->add_subcommand("ls", "List the entries, what each was made from and which device measured it");
  auto* verify = cmd->add_subcommand("verify", "Re-hash every entry and its inputs; name the stale and corrupt ones (exit 1 if any)");
  auto* clear = cmd->add_subcommand("clear", "Remove entries (all, or with --stale those verify names)");
  clear->add_flag("--stale", a->stale_only, "Only stale or corrupt entries");
  auto* build = cmd->add_subcommand("build", "Bake species into the cache ahead of time");
  build->add_option("presets", a->presets, "Species presets (.toml)");
  build->add_option("--scene", a->scene, "Every preset species of this scene, with its [bake]");
  build->add_option("--jobs", a->jobs, "Bakes at once (each on its own device context)")->check(CLI::Range(1, 64));
  build->add_option("--shard", a->shard, "i/n: only every n-th spec from the i-th (sorted by cache key), for array jobs");
  build->add_option("--priority", a->priority, "Presets' leaf order: random, density, orientation, combined, layered");
  build->add_option("--views", a->views, "Presets' PR views")->check(CLI::Range(1, 64));
  build->add_option("--resolution", a->resolution, "Presets' PR table size 0 (px)")->check(CLI::Range(kMinBakeResolution, kMaxPrSize0));
  build->add_flag("--no-impostor", a->no_impostor, "Presets baked without an impostor (quicker)");
  build->add_option("--device", a->device, kDeviceHelp);
  build->add_flag("--validate", a->validate, kValidateHelp);
  for (auto* sub : {ls, verify, clear, build}) sub->add_option("--cache", a->cache, kCacheHelp);
  return {cmd, [a, ls, verify, clear] {
            a->action = *ls ? "ls" : *verify ? "verify" : *clear ? "clear" : "build";
            return app::run_cache(*a);
          }};
}

// Every subcommand, in the order `forest --help` lists them.
std::vector<Command> add_commands(CLI::App& cli) {
  std::vector<Command> commands;
  for (Command (*add)(CLI::App&) : {add_info, add_generate, add_make_inputs, add_learn, add_preview, add_gallery,
                                    add_bake, add_report, add_measure, add_render, add_compare, add_walk, add_bench, add_export, add_cache})
    commands.push_back(add(cli));
  return commands;
}

// Parses the command line; an exit code when the run ends here (help, version, a usage
// error), nothing when a subcommand is to run.
std::optional<int> parse(CLI::App& cli, int argc, char** argv) {
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
  return std::nullopt;
}

// Runs the chosen subcommand; errors become one line on stderr and the exit code of
// commands.h (2 bad input, 1 internal failure).
int run_chosen(const std::vector<Command>& commands) {
  try {
    for (const Command& c : commands)
      if (*c.cli) return c.run();
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"forest: tree generators and a GPU-pruned forest renderer (Vulkan 1.3)"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "forest 0.1.0");
  std::vector<Command> commands = add_commands(cli);
  if (std::optional<int> code = parse(cli, argc, argv)) return *code;
  return run_chosen(commands);
}
