// forest bench: plays a scene's camera path in several prune modes and writes per-frame CSV,
// a JSON summary (Table 7.4: geometry and frame time relative to Cook, with Q alongside),
// plots along the path (Fig 7.17) and a raw triangle-throughput probe of the same device.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/tools/bake/species_cache.h"
#include "engine/app/app_common.h"
#include "engine/app/bench_summary.h"
#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "bench/bench_run.h"
#include "bench/bench_throughput.h"
#include "engine/present/image_io.h"
#include "engine/tools/report/plot.h"
#include "engine/scene/scene.h"
#include "generators/asset/asset_io.h"
#include "generators/asset/pr_tables.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {


std::string driver_name(const vk::Context& ctx) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  vkGetPhysicalDeviceProperties2(ctx.physical, &props);
  return std::string(driver.driverName) + " " + driver.driverInfo;
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}


// The inputs of a bench run, all checked before a Vulkan context exists.
struct BenchPlan {
  SceneDesc desc;
  size_t path = 0;                // the [[path]] played: an index into desc.paths
  std::vector<BenchMode> modes;   // in --modes order
  std::filesystem::path out;      // an existing folder
  std::vector<uint32_t> frames;   // path frames played
  const CameraPath& camera_path() const { return desc.paths[path]; }
};

// --shadows: the shadow settings every mode is played with, in order.
std::vector<bool> parse_shadows(const std::string& text, bool scene_default) {
  if (text.empty()) return {scene_default};
  if (text == "on") return {true};
  if (text == "off") return {false};
  if (text == "on,off") return {true, false};
  if (text == "off,on") return {false, true};
  throw InputError("--shadows", 0, text, "expected on, off or on,off");
}

std::string mode_list() {
  std::string list;
  for (const std::string& n : bench_mode_names()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

std::vector<BenchMode> parse_modes(const std::string& text) {
  std::vector<BenchMode> modes;
  std::stringstream list(text);
  std::string name;
  while (std::getline(list, name, ',')) {
    auto m = bench_mode(name);
    if (!m) throw InputError("--modes", 0, name, "unknown mode (" + mode_list() + ")");
    modes.push_back(*m);
  }
  if (modes.empty()) throw InputError("--modes", 0, "modes", "no mode given");
  return modes;
}

BenchPlan plan_bench(const BenchArgs& args) {
  BenchPlan plan;
  plan.desc = load_scene_file(args.scene);
  SceneDesc& desc = plan.desc;
  if (desc.paths.empty()) throw InputError(args.scene, 0, "path", "the scene has no [[path]] to play");
  const CameraPath* path = args.path.empty() ? &desc.paths.front() : find_path(desc, args.path);
  if (!path) throw InputError(args.scene, 0, "--path", "no [[path]] named '" + args.path + "'");
  plan.path = size_t(path - desc.paths.data());
  // With both settings played, the modes with shadows are named <mode>+shadows.
  const std::vector<bool> settings = parse_shadows(args.shadows, desc.shadows);
  for (bool shadows : settings)
    for (BenchMode m : parse_modes(args.modes)) {
      m.shadows = shadows;
      m.impostors = m.impostors || args.impostors.value_or(desc.impostors);
      if (shadows && settings.size() > 1) m.name += "+shadows";
      plan.modes.push_back(m);
    }
  plan.out = args.out;
  // A missing folder is made once the run has its results (write_bench_results), so bad
  // input leaves nothing behind.
  if (std::filesystem::exists(plan.out) && !std::filesystem::is_directory(plan.out))
    throw InputError(args.out, 0, "--out", "is not a folder");
  override_size(desc, args.width, args.height);
  plan.frames = bench_frames(*path, args.every, args.frames);
  return plan;
}

std::vector<BenchFrame> play_mode(vk::Context& ctx, const Scene& scene, const BenchPlan& plan, const BenchArgs& args,
                                  const BenchMode& mode, std::map<uint32_t, FrameImage>* references,
                                  MemoryReport* memory) {
  BenchPlayOptions play;
  play.width = plan.desc.width;
  play.height = plan.desc.height;
  play.frames = plan.frames;
  play.pr_every = args.pr_every;
  play.tree_pr = args.tree_pr;
  play.occlusion_warmup = args.occlusion_warmup;
  play.references = references;
  play.memory = memory;
  ProgressBar bar("bench " + mode.name);
  play.progress = [&](double f) { bar.update(f); };
  return play_bench_path(ctx, scene, plan.camera_path(), mode, play);
}

// The path once per mode. A mode with a priority order of its own (opt-density, ...) draws
// the species baked with that order: unless it is the scene's own, that scene is built on
// first use and keeps full-detail references of its own (they differ with the leaf order).
std::vector<ModeSummary> play_modes(vk::Context& ctx, const Scene& scene, const SceneBuildOptions& build,
                                    const BenchPlan& plan, const BenchArgs& args) {
  std::map<std::string, Scene> ordered;  // by priority order, the scene's own excluded
  std::vector<ModeSummary> results;
  std::map<std::string, std::map<uint32_t, FrameImage>> references;  // full-detail coverage per order and frame
  // With --tree-pr, the first mode a process plays draws a window of its frames 2-4x slower
  // than the same mode played again later in the run (lavapipe; bench_grove, 8 runs of 8:
  // `cook,opt,cook` 140.8 ms then 48.9 ms a frame; less so with glibc told never to return
  // memory, so likely the allocator's first growth). The first mode, when it draws the scene's
  // own order, is played once unrecorded (the references it renders are kept).
  if (args.tree_pr && !plan.modes.empty() && plan.modes.front().priority.empty()) {
    MemoryReport ignored;
    play_mode(ctx, scene, plan, args, plan.modes.front(), &references[plan.desc.bake.priority], &ignored);
  }
  for (const BenchMode& mode : plan.modes) {
    const Scene* s = &scene;
    const std::string order = mode.priority.empty() ? plan.desc.bake.priority : mode.priority;
    std::map<uint32_t, FrameImage>* refs = &references[order];
    if (order != plan.desc.bake.priority) {
      if (!ordered.count(order)) {
        SceneDesc d = plan.desc;
        d.bake.priority = order;
        ordered.emplace(order, build_scene(d, build));
      }
      s = &ordered.at(order);
    }
    MemoryReport memory;
    results.push_back(summarize(mode, play_mode(ctx, *s, plan, args, mode, refs, &memory)));
    results.back().memory = memory;
  }
  return results;
}

// Raw triangle throughput of the device at the bench's resolution (none when instances is 0).
ThroughputResult probe_throughput(vk::Context& ctx, const SceneDesc& desc, uint32_t instances) {
  ThroughputOptions probe;
  probe.width = desc.width;
  probe.height = desc.height;
  probe.instances = instances;
  ThroughputResult raw;
  if (probe.instances) raw = measure_triangle_throughput(ctx, probe);
  return raw;
}

// What the summaries are written from.
struct BenchReport {
  const BenchArgs& args;
  const BenchPlan& plan;
  const std::vector<ModeSummary>& modes;
  // Cook played with the same shadow setting as `m` (null when it was not).
  const ModeSummary* cook(const ModeSummary& m) const {
    for (const ModeSummary& c : modes)
      if (c.mode.prune_mode == PruneMode::cook && !c.mode.occlusion && c.mode.shadows == m.mode.shadows) return &c;
    return nullptr;
  }
  size_t instances;         // trees in the scene
  ThroughputResult raw;
  std::string device, driver;
};

// One mode against Cook's and against the throughput probe.
struct VsCook {
  double tris_per_s = 0, throughput_fraction = 0;
  bool measured = false;                     // Cook was played and drew, in measurable time
  double geo = 0, time = 0, leaf_ratio = 0;  // ratios to Cook's; 0 unless measured
  bool q_ok = false;
  std::string q_delta = "-";  // Q - Q_cook, signed; "-" without PR frames on both sides
};

VsCook compare_to_cook(const ModeSummary& m, const ModeSummary* cook, const ThroughputResult& raw) {
  VsCook v;
  v.tris_per_s = m.gpu_draw_ms > 0 ? m.triangles / (m.gpu_draw_ms * 1e-3) : 0.0;
  v.throughput_fraction = raw.triangles_per_second() > 0 ? v.tris_per_s / raw.triangles_per_second() : 0.0;
  if (cook && cook->triangles > 0 && cook->gpu_frame_ms > 0) {
    v.measured = true;
    v.geo = m.triangles / cook->triangles, v.time = m.gpu_frame_ms / cook->gpu_frame_ms;
    v.q_ok = m.quality >= cook->quality - kEqualQualityTolerance;
    v.leaf_ratio = cook->leaves > 0 ? m.leaves / cook->leaves : 0.0;
  }
  // Q against Cook's, signed: "equal Q" is a judgement the reader makes from the number.
  if (cook && m.pr_frames && cook->pr_frames) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.5f", m.quality - cook->quality);
    v.q_delta = text;
  }
  return v;
}

nlohmann::ordered_json summary_header(const BenchReport& r) {
  const SceneDesc& desc = r.plan.desc;
  nlohmann::ordered_json j;
  j["scene"] = r.args.scene;
  j["path"] = r.plan.camera_path().name;
  j["fps"] = r.plan.camera_path().fps;
  j["frames"] = r.plan.frames.size();
  j["pr_every"] = r.args.pr_every;
  j["tree_pr"] = r.args.tree_pr;
  j["device"] = r.device;
  j["driver"] = r.driver;
  j["resolution"] = {desc.width, desc.height};
  j["samples"] = desc.samples;
  j["instances"] = r.instances;
  j["date"] = utc_now();
  j["throughput_probe"] = {{"triangles_per_frame", r.raw.triangles_per_frame},
                           {"gpu_draw_ms", r.raw.draw_ms},
                           {"triangles_per_second", r.raw.triangles_per_second()}};
  return j;
}

void add_vs_cook_json(nlohmann::ordered_json& e, const ModeSummary& m, const ModeSummary& cook, const VsCook& v) {
  e["geometry_vs_cook"] = v.geo;
  e["leaves_vs_cook"] = v.leaf_ratio;  // foliage alone, as Neubert 2012's Table 7.4 counts it
  e["frame_time_vs_cook"] = v.time;
  e["frame_rate_vs_cook"] = v.time > 0 ? 1.0 / v.time : 0.0;
  e["q_equal_to_cook"] = v.q_ok;  // Q >= Q_cook - kEqualQualityTolerance
  if (m.pr_frames && cook.pr_frames) e["q_minus_cook"] = m.quality - cook.quality;
  std::vector<double> along;
  for (size_t i = 0; i < m.frames.size() && i < cook.frames.size(); ++i)
    along.push_back(cook.frames[i].tree_triangles ? double(m.frames[i].tree_triangles) /
                                                        double(cook.frames[i].tree_triangles)
                                                  : 0.0);
  e["geometry_vs_cook_along_path"] = along;
}

nlohmann::ordered_json mode_json(const ModeSummary& m, const ModeSummary* cook, const VsCook& v) {
  nlohmann::ordered_json e;
  e["frames"] = m.frames.size();
  e["gpu_frame_ms"] = m.gpu_frame_ms;
  e["gpu_cull_ms"] = m.gpu_cull_ms;
  e["gpu_draw_ms"] = m.gpu_draw_ms;
  e["gpu_pyramid_ms"] = m.gpu_pyramid_ms;
  e["cpu_ms"] = m.cpu_ms;
  e["tree_triangles"] = m.triangles;
  e["tree_vertices_ia"] = m.vertices;
  e["leaves_drawn"] = m.leaves;
  e["instances_visible"] = m.visible;
  e["mean_lambda"] = m.lambda;
  if (m.mode.occlusion)  // what occlusion feedback saved against the same mode without it, per frame
    e["occlusion"] = {{"leaves_saved", m.leaves_saved},
                      {"leaves_saved_share", m.leaves_saved_share()},
                      {"triangles_saved", m.triangles_saved},
                      {"triangles_saved_share", m.triangles_saved_share()},
                      {"instances_culled", m.occluded},
                      {"gpu_pyramid_and_cull_share", m.occlusion_gpu_share()}};
  e["impostors_on"] = m.mode.impostors;
  if (m.mode.impostors) e["impostors_drawn"] = m.impostors;
  e["shadows_on"] = m.mode.shadows;
  if (m.mode.shadows)
    e["shadows"] = {{"gpu_shadow_ms", m.gpu_shadow_ms},
                    {"gpu_frame_share", m.gpu_frame_ms > 0 ? m.gpu_shadow_ms / m.gpu_frame_ms : 0.0},
                    {"casters_per_cascade", m.shadow_casters},
                    {"impostor_casters_per_cascade", m.shadow_impostors},
                    {"triangles_per_cascade", m.shadow_triangles}};
  if (TreePr t = tree_pr(m); t.frames)
    e["tree_pr"] = {{"frames", t.frames}, {"min_trees_per_frame", t.min_trees}, {"mean_q", t.mean},
                    {"worst_frame_mean_q", t.worst_mean}, {"worst_frame_p10_q", t.worst_p10}, {"p10_q", t.p10}};
  e["pr_frames"] = m.pr_frames;
  e["precision"] = m.precision;
  e["recall"] = m.recall;
  e["q"] = m.quality;
  e["triangles_per_second"] = v.tris_per_s;
  e["throughput_fraction"] = v.throughput_fraction;
  if (v.measured) add_vs_cook_json(e, m, *cook, v);
  return e;
}

void print_bench_header(const BenchReport& r) {
  const SceneDesc& desc = r.plan.desc;
  std::printf("%s on %s (%s), %ux%u, %zu frames of path '%s'\n", r.args.scene.c_str(), r.device.c_str(),
              r.driver.c_str(), desc.width, desc.height, r.plan.frames.size(), r.plan.camera_path().name.c_str());
  std::printf("raw throughput: %.1f M triangles/s (%llu triangles in %.2f ms)\n", r.raw.triangles_per_second() * 1e-6,
              (unsigned long long)r.raw.triangles_per_frame, r.raw.draw_ms);
}

void print_mode_row(const ModeSummary& m, const ModeSummary* cook, const VsCook& v) {
  std::printf("%-13s %10.0f %10s %9.2f %9s %7.4f %8s %9.3f %8.1f%%\n", m.mode.name.c_str(), m.triangles,
              cook ? (std::to_string(int(std::lround(v.geo * 100))) + "%").c_str() : "-", m.gpu_frame_ms,
              cook ? (std::to_string(int(std::lround(v.time * 100))) + "%").c_str() : "-", m.quality,
              v.q_delta.c_str(), m.lambda, 100.0 * v.throughput_fraction);
}

// summary.md: Table 7.4 style.
std::string markdown_header(const BenchReport& r) {
  const SceneDesc& desc = r.plan.desc;
  const CameraPath& path = r.plan.camera_path();
  std::ostringstream md;
  md << "# forest bench: " << r.args.scene << ", path '" << path.name << "'\n\n"
     << "Device **" << r.device << "** (driver " << r.driver << "), " << desc.width << "x" << desc.height << ", "
     << desc.samples << " sample(s)/pixel, " << r.instances << " trees, " << r.plan.frames.size()
     << " frames at " << path.fps << " fps (every " << r.args.every << "), PR every " << r.args.pr_every
     << " played frames; " << utc_now() << ".\n\n"
     << "Raw throughput probe: " << r.raw.triangles_per_frame << " triangles in " << r.raw.draw_ms << " ms GPU draw = "
     << r.raw.triangles_per_second() * 1e-6 << " M triangles/s.\n\n"
     << "| mode | tree triangles | vs Cook | leaves | vs Cook | GPU frame ms | vs Cook | frame rate vs Cook | mean Q | "
        "Q - Q_cook | mean lambda | triangles/s of probe |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  return md.str();
}

std::string cell(bool known, const char* format, double value) {  // "-" for what was not measured
  char text[32] = "-";
  if (known) std::snprintf(text, sizeof text, format, value);
  return std::string(text);
}

std::string markdown_row(const ModeSummary& m, const ModeSummary* cook, const VsCook& v) {
  auto vs_cook = [&](const char* format, double value) { return cell(cook != nullptr, format, value); };
  char row[512];
  std::snprintf(row, sizeof row, "| %s | %.0f | %s | %.0f | %s | %.2f | %s | %s | %s | %s | %.3f | %.1f%% |\n",
                m.mode.name.c_str(), m.triangles, vs_cook("%.1f%%", 100.0 * v.geo).c_str(), m.leaves,
                vs_cook("%.1f%%", 100.0 * v.leaf_ratio).c_str(), m.gpu_frame_ms,
                vs_cook("%.1f%%", 100.0 * v.time).c_str(), vs_cook("%.2fx", v.time > 0 ? 1.0 / v.time : 0.0).c_str(),
                cell(m.pr_frames > 0, "%.4f", m.quality).c_str(), v.q_delta.c_str(), m.lambda,
                100.0 * v.throughput_fraction);
  return row;
}

// A paragraph of summary.md (it starts with an empty line) on what occlusion feedback saved.
std::string occlusion_note(const ModeSummary& m) {
  char row[640];
  std::snprintf(row, sizeof row,
                "\nOcclusion feedback (%s), mean per frame: %.0f leaves saved (%.1f %% of what the mode alone "
                "draws), %.0f triangles saved (%.1f %%), %.1f trees culled; depth pyramid %.3f ms + cull %.3f ms "
                "= %.2f %% of the GPU frame (goal <= 5 %%).\n",
                m.mode.name.c_str(), m.leaves_saved, 100.0 * m.leaves_saved_share(), m.triangles_saved,
                100.0 * m.triangles_saved_share(), m.occluded, m.gpu_pyramid_ms, m.gpu_cull_ms,
                100.0 * m.occlusion_gpu_share());
  return row;
}

// A paragraph of summary.md on what the sun's shadows cost `m` (a mode played with them),
// against the same mode without them when that was played too.
std::string shadow_note(const ModeSummary& m, const std::vector<ModeSummary>& modes) {
  const ModeSummary* off = nullptr;
  for (const ModeSummary& o : modes)
    if (!o.mode.shadows && o.mode.prune_mode == m.mode.prune_mode && o.mode.occlusion == m.mode.occlusion &&
        o.mode.priority == m.mode.priority && o.mode.impostors == m.mode.impostors &&
        o.mode.instanced_leaves == m.mode.instanced_leaves)
      off = &o;
  char row[768];
  std::snprintf(row, sizeof row,
                "\nShadows (%s), mean per frame: shadow pass %.2f ms = %.1f %% of the GPU frame (goal <= 35 %% on "
                "lavapipe); casters per cascade %.0f / %.0f / %.0f, shadow triangles %.0f / %.0f / %.0f",
                m.mode.name.c_str(), m.gpu_shadow_ms, m.gpu_frame_ms > 0 ? 100.0 * m.gpu_shadow_ms / m.gpu_frame_ms : 0.0,
                m.shadow_casters[0], m.shadow_casters[1], m.shadow_casters[2], m.shadow_triangles[0],
                m.shadow_triangles[1], m.shadow_triangles[2]);
  std::string note = row;
  if (off && off->gpu_frame_ms > 0) {
    std::snprintf(row, sizeof row, "; GPU frame time with shadows / without (%s): %.2fx", off->mode.name.c_str(),
                  m.gpu_frame_ms / off->gpu_frame_ms);
    note += row;
  }
  return note + ".\n";
}

// A paragraph of summary.md on the device memory one mode's renderer holds (every mode
// holds the same scene, the same targets and the same passes).
std::string memory_note(const MemoryReport& m) {
  auto mib = [](uint64_t b) { return double(b) / double(1 << 20); };
  char text[512];
  std::snprintf(text, sizeof text,
                "\nDevice memory of the scene: %.1f MiB (geometry %.1f, leaf and bark textures %.1f, impostors %.1f, "
                "shadow map %.1f, render targets %.1f, per-frame passes %.1f).\n",
                mib(m.total()), mib(m.geometry), mib(m.textures), mib(m.impostors), mib(m.shadows), mib(m.targets),
                mib(m.passes));
  return text;
}

nlohmann::ordered_json memory_json(const MemoryReport& m) {
  return {{"total", m.total()},       {"geometry", m.geometry}, {"textures", m.textures}, {"impostors", m.impostors},
          {"shadows", m.shadows},     {"targets", m.targets},   {"passes", m.passes}};
}

// summary.json, summary.md, frames_<mode>.csv and the two plots, with the table on stdout.
void write_bench_results(const BenchReport& r) {
  const SceneDesc& desc = r.plan.desc;
  const std::filesystem::path& out = r.plan.out;
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError(out.string(), 0, "--out", "cannot create folder: " + ec.message());
  std::string label = r.device + ", " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + ", " +
                      std::filesystem::path(r.args.scene).filename().string();
  nlohmann::ordered_json j = summary_header(r);
  print_bench_header(r);
  std::ostringstream md;
  md << markdown_header(r);
  std::printf("%-13s %10s %10s %9s %9s %7s %7s %9s %9s\n", "mode", "triangles", "vs cook", "frame ms",
              "vs cook", "Q", "Q-cook", "mean lam", "tri/s %");
  for (const ModeSummary& m : r.modes) {
    const ModeSummary* cook = r.cook(m);
    VsCook v = compare_to_cook(m, cook, r.raw);
    j["modes"][m.mode.name] = mode_json(m, cook, v);
    print_mode_row(m, cook, v);
    md << markdown_row(m, cook, v);
    write_text_file(out / ("frames_" + m.mode.name + ".csv"), frames_csv(m));
    if (std::string trees = trees_csv(m); !trees.empty()) write_text_file(out / ("trees_" + m.mode.name + ".csv"), trees);
  }
  for (const ModeSummary& m : r.modes) {
    if (!m.mode.occlusion) continue;
    std::string note = occlusion_note(m);
    md << note;
    std::printf("%s", note.c_str() + 1);
  }
  for (const ModeSummary& m : r.modes) {
    if (!m.mode.shadows) continue;
    std::string note = shadow_note(m, r.modes);
    md << note;
    std::printf("%s", note.c_str() + 1);
  }
  for (const ModeSummary& m : r.modes) {
    std::string note = tree_pr_note(m, desc.quality);
    md << note;
    std::printf("%s", note.c_str());
  }
  if (!r.modes.empty()) {
    std::string note = memory_note(r.modes.front().memory);
    md << note;
    std::printf("%s", note.c_str() + 1);
    j["device_memory_bytes"] = memory_json(r.modes.front().memory);
  }
  const std::string table = table_7_4_note(r.modes, [&](const ModeSummary& m) { return r.cook(m); }, out / "saved.png", label);
  md << table;
  std::printf("%s", table.c_str());
  write_text_file(out / "summary.json", j.dump(2) + "\n");
  md << "\nGoals (this project's, beyond Neubert 2012 §7.6): >= 45 % less geometry than Cook and >= 2x its frame rate at equal Q "
        "(the paper: 30.1 %, ~1.67x); Q - Q_cook >= -"
     << tolerance_text() << " is taken as equal Q. Plots: triangles.png, frame_time.png (and saved.png with a Cook mode); per frame: frames_<mode>.csv.\n";
  write_text_file(out / "summary.md", md.str());
  write_path_plot(r.modes, "tree triangles per frame (" + label + ")", "triangles",
                  [](const BenchFrame& f) { return double(f.tree_triangles); }, out / "triangles.png");
  write_path_plot(r.modes, "GPU frame time (" + label + ")", "ms",
                  [](const BenchFrame& f) { return f.stats.frame_ms; }, out / "frame_time.png");
  std::printf("wrote %s: summary.json, summary.md, frames_<mode>.csv, triangles.png, frame_time.png\n", out.c_str());
}

}  // namespace

int run_bench(const BenchArgs& args) {
  BenchPlan plan = plan_bench(args);
  SpeciesCacheOptions cache;
  cache.dir = args.cache;
  cache.log = print_line;

  CommandContext context(context_options(args.device, args.validate));
  vk::Context& ctx = context.ctx;
  cache.ctx = &ctx;
  SceneBuildOptions build;
  build.species = cached_species_source(cache);
  Scene scene = build_scene(plan.desc, build);
  std::vector<ModeSummary> results = play_modes(ctx, scene, build, plan, args);
  ThroughputResult raw = probe_throughput(ctx, plan.desc, args.probe_instances);
  if (validation_failed(ctx, "results", true)) return 1;
  write_bench_results({args, plan, results, scene.instances.size(), raw,
                       ctx.properties.deviceName, driver_name(ctx)});
  return 0;
}

}  // namespace forest::app
