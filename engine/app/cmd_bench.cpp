// forest bench: plays a scene's camera path in several prune modes and writes per-frame CSV,
// a JSON summary (Table 7.4: geometry and frame time relative to Cook, with Q alongside),
// plots along the path (Fig 7.17) and a raw triangle-throughput probe of the same device.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/tools/bake/species_cache.h"
#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "bench/bench_run.h"
#include "bench/bench_throughput.h"
#include "engine/present/image_io.h"
#include "engine/tools/report/plot.h"
#include "engine/scene/scene.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

struct ModeSummary {
  BenchMode mode;
  std::vector<BenchFrame> frames;
  double gpu_frame_ms = 0, gpu_draw_ms = 0, gpu_cull_ms = 0, gpu_pyramid_ms = 0, cpu_ms = 0;
  double triangles = 0, vertices = 0, leaves = 0, visible = 0, lambda = 0, quality = 0, precision = 0, recall = 0;
  double leaves_saved = 0, triangles_saved = 0, occluded = 0;  // by occlusion feedback, per frame
  uint32_t pr_frames = 0;
  // Shares of what the mode would draw without occlusion, and of the GPU frame.
  double leaves_saved_share() const { return leaves_saved / std::max(leaves + leaves_saved, 1.0); }
  double triangles_saved_share() const { return triangles_saved / std::max(triangles + triangles_saved, 1.0); }
  double occlusion_gpu_share() const { return gpu_frame_ms > 0 ? (gpu_pyramid_ms + gpu_cull_ms) / gpu_frame_ms : 0.0; }
};

ModeSummary summarize(const BenchMode& mode, std::vector<BenchFrame> frames) {
  ModeSummary s;
  s.mode = mode;
  double n = double(std::max<size_t>(frames.size(), 1));
  for (const BenchFrame& f : frames) {
    s.gpu_frame_ms += f.stats.frame_ms / n, s.gpu_draw_ms += f.stats.draw_ms / n, s.gpu_cull_ms += f.stats.cull_ms / n;
    s.gpu_pyramid_ms += f.stats.pyramid_ms / n, s.cpu_ms += f.stats.cpu_submit_ms / n;
    s.triangles += double(f.tree_triangles) / n, s.vertices += 3.0 * double(f.tree_triangles) / n;
    s.leaves += f.stats.leaves_drawn / n, s.visible += f.stats.branch_draws / n, s.lambda += f.stats.mean_lambda / n;
    s.leaves_saved += f.stats.leaves_saved / n, s.triangles_saved += f.stats.triangles_saved / n;
    s.occluded += f.stats.occluded_instances / n;
    if (f.has_pr) {
      s.pr_frames++;
      s.quality += f.pr.quality(), s.precision += f.pr.precision(), s.recall += f.pr.recall();
    }
  }
  if (s.pr_frames) s.quality /= s.pr_frames, s.precision /= s.pr_frames, s.recall /= s.pr_frames;
  s.frames = std::move(frames);
  return s;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

std::string frames_csv(const ModeSummary& m) {
  std::ostringstream o;
  o << "frame,time_s,gpu_cull_ms,gpu_draw_ms,gpu_pyramid_ms,gpu_frame_ms,cpu_ms,ia_primitives,tree_triangles,"
       "branch_triangles,leaves_drawn,instances_visible,occluded_instances,leaves_saved,triangles_saved,mean_lambda,"
       "precision,recall,q\n";
  char buf[512];
  for (const BenchFrame& f : m.frames) {
    const FrameStats& s = f.stats;
    std::snprintf(buf, sizeof buf, "%u,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,%llu,%u,%u,%u,%u,%u,%u,%.5f,", f.frame,
                  f.time, s.cull_ms, s.draw_ms, s.pyramid_ms, s.frame_ms, s.cpu_submit_ms,
                  (unsigned long long)s.draw_pipeline.ia_primitives, (unsigned long long)f.tree_triangles,
                  s.branch_triangles, s.leaves_drawn, s.branch_draws, s.occluded_instances, s.leaves_saved,
                  s.triangles_saved, s.mean_lambda);
    o << buf;
    if (f.has_pr) {
      std::snprintf(buf, sizeof buf, "%.5f,%.5f,%.5f", f.pr.precision(), f.pr.recall(), f.pr.quality());
      o << buf;
    } else {
      o << ",,";
    }
    o << "\n";
  }
  return o.str();
}

glm::vec3 mode_color(const std::string& name) {
  if (name == "full") return {0.1f, 0.1f, 0.1f};
  if (name == "cook") return {0.85f, 0.25f, 0.15f};
  if (name == "opt") return {0.1f, 0.35f, 0.85f};
  if (name == "opt-combined") return {0.1f, 0.65f, 0.3f};
  return {0.6f, 0.2f, 0.7f};
}

void write_path_plot(const std::vector<ModeSummary>& modes, const std::string& title, const std::string& y_label,
                     double (*value)(const BenchFrame&), const std::filesystem::path& file) {
  Plot p;
  p.title = title;
  p.x_label = "time along the path (s)";
  p.y_label = y_label;
  p.width = 900;
  for (const ModeSummary& m : modes) {
    PlotSeries s;
    s.label = m.mode.name;
    s.color = mode_color(m.mode.name);
    for (const BenchFrame& f : m.frames) s.points.push_back({float(f.time), float(value(f))});
    p.series.push_back(std::move(s));
  }
  p.x_range = padded_range(p.series, 0, 0.0f);
  p.y_range = padded_range(p.series, 1);
  p.y_range.x = 0.0f;
  write_plot(p, file);
}

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

}  // namespace

int run_bench(const BenchArgs& args) {
  SceneDesc desc = load_scene_file(args.scene);
  if (desc.paths.empty()) throw InputError(args.scene, 0, "path", "the scene has no [[path]] to play");
  const CameraPath* path = args.path.empty() ? &desc.paths.front() : find_path(desc, args.path);
  if (!path) throw InputError(args.scene, 0, "--path", "no [[path]] named '" + args.path + "'");
  std::vector<BenchMode> modes;
  {
    std::stringstream list(args.modes);
    std::string name;
    while (std::getline(list, name, ',')) {
      auto m = bench_mode(name);
      if (!m) throw InputError("--modes", 0, name, "unknown mode (full, cook, opt, opt-combined, opt-occl)");
      modes.push_back(*m);
    }
    if (modes.empty()) throw InputError("--modes", 0, "modes", "no mode given");
  }
  std::filesystem::path out = args.out;
  if (!std::filesystem::is_directory(out))
    throw InputError(args.out, 0, "--out", "is not an existing folder");
  if (args.width) desc.width = *args.width;
  if (args.height) desc.height = *args.height;
  std::vector<uint32_t> frame_list = bench_frames(*path, args.every, args.frames);

  SpeciesCacheOptions cache;
  cache.dir = args.cache;
  cache.log = [](const std::string& line) { std::printf("%s\n", line.c_str()), std::fflush(stdout); };

  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = args.validate || vk::validation_from_env();
  int code = 0;
  try {
    vk::create_context(ctx, options);
    cache.ctx = &ctx;
    SceneBuildOptions build;
    build.species = cached_species_source(cache);
    Scene scene = build_scene(desc, build);
    std::optional<Scene> combined;  // opt-combined: the species baked with the combined priority
    std::vector<ModeSummary> results;
    std::map<uint32_t, FrameImage> references, combined_references;  // full-detail coverage per frame
    for (const BenchMode& mode : modes) {
      const Scene* s = &scene;
      std::map<uint32_t, FrameImage>* refs = &references;
      if (mode.combined_priority && desc.bake.priority != "combined") {
        if (!combined) {
          SceneDesc d = desc;
          d.bake.priority = "combined";
          combined = build_scene(d, build);
        }
        s = &*combined;
        refs = &combined_references;
      }
      BenchPlayOptions play;
      play.width = desc.width;
      play.height = desc.height;
      play.frames = frame_list;
      play.pr_every = args.pr_every;
      play.occlusion_warmup = args.occlusion_warmup;
      play.references = refs;
      ProgressBar bar("bench " + mode.name);
      play.progress = [&](double f) { bar.update(f); };
      results.push_back(summarize(mode, play_bench_path(ctx, *s, *path, mode, play)));
    }
    ThroughputOptions probe;
    probe.width = desc.width;
    probe.height = desc.height;
    probe.instances = args.probe_instances;
    ThroughputResult raw;
    if (probe.instances) raw = measure_triangle_throughput(ctx, probe);

    if (ctx.validation_messages > 0) {
      std::fprintf(stderr, "forest: %u Vulkan validation message(s); no results written (last: %s)\n",
                   ctx.validation_messages.load(), ctx.last_validation_message.c_str());
      code = 1;
    } else {
      const ModeSummary* cook = nullptr;
      for (const ModeSummary& m : results)
        if (m.mode.name == "cook") cook = &m;
      std::string device = ctx.properties.deviceName, driver = driver_name(ctx);
      std::string label = device + ", " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + ", " +
                          std::filesystem::path(args.scene).filename().string();
      nlohmann::ordered_json j;
      j["scene"] = args.scene;
      j["path"] = path->name;
      j["fps"] = path->fps;
      j["frames"] = frame_list.size();
      j["pr_every"] = args.pr_every;
      j["device"] = device;
      j["driver"] = driver;
      j["resolution"] = {desc.width, desc.height};
      j["samples"] = desc.samples;
      j["instances"] = scene.instances.size();
      j["date"] = utc_now();
      j["throughput_probe"] = {{"triangles_per_frame", raw.triangles_per_frame},
                               {"gpu_draw_ms", raw.draw_ms},
                               {"triangles_per_second", raw.triangles_per_second()}};
      std::printf("%s on %s (%s), %ux%u, %zu frames of path '%s'\n", args.scene.c_str(), device.c_str(),
                  driver.c_str(), desc.width, desc.height, frame_list.size(), path->name.c_str());
      std::printf("raw throughput: %.1f M triangles/s (%llu triangles in %.2f ms)\n", raw.triangles_per_second() * 1e-6,
                  (unsigned long long)raw.triangles_per_frame, raw.draw_ms);
      std::ostringstream md;  // summary.md: Table 7.4 style
      md << "# forest bench: " << args.scene << ", path '" << path->name << "'\n\n"
         << "Device **" << device << "** (driver " << driver << "), " << desc.width << "x" << desc.height << ", "
         << desc.samples << " sample(s)/pixel, " << scene.instances.size() << " trees, " << frame_list.size()
         << " frames at " << path->fps << " fps (every " << args.every << "), PR every " << args.pr_every
         << " played frames; " << utc_now() << ".\n\n"
         << "Raw throughput probe: " << raw.triangles_per_frame << " triangles in " << raw.draw_ms << " ms GPU draw = "
         << raw.triangles_per_second() * 1e-6 << " M triangles/s.\n\n"
         << "| mode | tree triangles | vs Cook | leaves | vs Cook | GPU frame ms | vs Cook | frame rate vs Cook | mean Q | "
            "Q - Q_cook | mean lambda | triangles/s of probe |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
      std::printf("%-13s %10s %10s %9s %9s %7s %7s %9s %9s\n", "mode", "triangles", "vs cook", "frame ms",
                  "vs cook", "Q", "Q-cook", "mean lam", "tri/s %");
      for (ModeSummary& m : results) {
        double tris_per_s = m.gpu_draw_ms > 0 ? m.triangles / (m.gpu_draw_ms * 1e-3) : 0.0;
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
        e["pr_frames"] = m.pr_frames;
        e["precision"] = m.precision;
        e["recall"] = m.recall;
        e["q"] = m.quality;
        e["triangles_per_second"] = tris_per_s;
        e["throughput_fraction"] = raw.triangles_per_second() > 0 ? tris_per_s / raw.triangles_per_second() : 0.0;
        double geo = 0, time = 0, leaf_ratio = 0;
        bool q_ok = false;
        if (cook && cook->triangles > 0 && cook->gpu_frame_ms > 0) {
          geo = m.triangles / cook->triangles, time = m.gpu_frame_ms / cook->gpu_frame_ms;
          q_ok = m.quality >= cook->quality;
          leaf_ratio = cook->leaves > 0 ? m.leaves / cook->leaves : 0.0;
          e["geometry_vs_cook"] = geo;
          e["leaves_vs_cook"] = leaf_ratio;  // foliage alone, as Neubert 2012's Table 7.4 counts it
          e["frame_time_vs_cook"] = time;
          e["frame_rate_vs_cook"] = time > 0 ? 1.0 / time : 0.0;
          e["q_at_least_cook"] = q_ok;
          if (m.pr_frames && cook->pr_frames) e["q_minus_cook"] = m.quality - cook->quality;
          std::vector<double> along;
          for (size_t i = 0; i < m.frames.size() && i < cook->frames.size(); ++i)
            along.push_back(cook->frames[i].tree_triangles ? double(m.frames[i].tree_triangles) /
                                                                 double(cook->frames[i].tree_triangles)
                                                           : 0.0);
          e["geometry_vs_cook_along_path"] = along;
        }
        j["modes"][m.mode.name] = e;
        // Q against Cook's, signed: "equal Q" is a judgement the reader makes from the number.
        std::string q_delta = "-";
        if (cook && m.pr_frames && cook->pr_frames) {
          char text[32];
          std::snprintf(text, sizeof text, "%+.5f", m.quality - cook->quality);
          q_delta = text;
        }
        std::printf("%-13s %10.0f %10s %9.2f %9s %7.4f %8s %9.3f %8.1f%%\n", m.mode.name.c_str(), m.triangles,
                    cook ? (std::to_string(int(std::lround(geo * 100))) + "%").c_str() : "-", m.gpu_frame_ms,
                    cook ? (std::to_string(int(std::lround(time * 100))) + "%").c_str() : "-", m.quality,
                    q_delta.c_str(), m.lambda,
                    100.0 * (raw.triangles_per_second() > 0 ? tris_per_s / raw.triangles_per_second() : 0.0));
        char row[512];
        auto cell = [](bool known, const char* format, double value) {  // "-" for what was not measured
          char text[32] = "-";
          if (known) std::snprintf(text, sizeof text, format, value);
          return std::string(text);
        };
        auto vs_cook = [&](const char* format, double value) { return cell(cook != nullptr, format, value); };
        std::snprintf(row, sizeof row, "| %s | %.0f | %s | %.0f | %s | %.2f | %s | %s | %s | %s | %.3f | %.1f%% |\n",
                      m.mode.name.c_str(), m.triangles, vs_cook("%.1f%%", 100.0 * geo).c_str(), m.leaves,
                      vs_cook("%.1f%%", 100.0 * leaf_ratio).c_str(), m.gpu_frame_ms,
                      vs_cook("%.1f%%", 100.0 * time).c_str(), vs_cook("%.2fx", time > 0 ? 1.0 / time : 0.0).c_str(),
                      cell(m.pr_frames > 0, "%.4f", m.quality).c_str(),
                      q_delta.c_str(), m.lambda,
                      100.0 * (raw.triangles_per_second() > 0 ? tris_per_s / raw.triangles_per_second() : 0.0));
        md << row;
        write_text(out / ("frames_" + m.mode.name + ".csv"), frames_csv(m));
      }
      for (const ModeSummary& m : results) {
        if (!m.mode.occlusion) continue;
        char row[640];
        std::snprintf(row, sizeof row,
                      "\nOcclusion feedback (%s), mean per frame: %.0f leaves saved (%.1f %% of what the mode alone "
                      "draws), %.0f triangles saved (%.1f %%), %.1f trees culled; depth pyramid %.3f ms + cull %.3f ms "
                      "= %.2f %% of the GPU frame (goal <= 5 %%).\n",
                      m.mode.name.c_str(), m.leaves_saved, 100.0 * m.leaves_saved_share(), m.triangles_saved,
                      100.0 * m.triangles_saved_share(), m.occluded, m.gpu_pyramid_ms, m.gpu_cull_ms,
                      100.0 * m.occlusion_gpu_share());
        md << row;
        std::printf("%s", row + 1);
      }
      write_text(out / "summary.json", j.dump(2) + "\n");
      md << "\nGoals (Neubert 2012 §7.6, forest issue 9): >= 45 % less geometry than Cook and >= 2x its frame rate at equal Q "
            "(paper: 30.1 %, ~1.67x); Q - Q_cook >= -0.001 is taken as equal Q. Plots: triangles.png, frame_time.png; per frame: frames_<mode>.csv.\n";
      write_text(out / "summary.md", md.str());
      write_path_plot(results, "tree triangles per frame (" + label + ")", "triangles",
                      [](const BenchFrame& f) { return double(f.tree_triangles); }, out / "triangles.png");
      write_path_plot(results, "GPU frame time (" + label + ")", "ms",
                      [](const BenchFrame& f) { return f.stats.frame_ms; }, out / "frame_time.png");
      std::printf("wrote %s: summary.json, summary.md, frames_<mode>.csv, triangles.png, frame_time.png\n", out.c_str());
    }
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  return code;
}

}  // namespace forest::app
