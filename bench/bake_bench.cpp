// Bake timing and the rendering-priority comparison of Neubert 2012 Table 7.4. Usage:
//   bake_bench [--model SPECIES.toml] [--old-model SPECIES.toml] [--compare SPECIES.toml]...
//              [--views N] [--resolution PX] [--out DIR] [--skip-time] [--skip-compare]
//              [--orders random,density,...] [--tables]
// 1. Bake time of --model (default bench/species/mig_a_50k.toml, ~51 K leaves) by stage:
//    hull, priority (combined), PR references, PR pruned renders + counts (+ readback).
// 2. The same PR measurement on --old-model (default scenes/species/broadleaf.toml) with the
//    original path (one submit per render, branches redrawn, every s on the grid) and with
//    the current one: the ratio, and how far the tables moved.
// 3. Table 7.4: for every --compare model (default broadleaf, particle_flow_oak_hero, mig_a_hero)
//    and every priority order, the detail λ needed to match the quality of Cook et al.
//    (random order, s = 1/λ, at λ_Cook(d) = (1 − d)²) with that order's s_opt, along
//    d = 0.1 … 0.7: geometry saved = 1 − λ/λ_Cook. "random" is the paper's "Opt PR" column.
//    Writes DIR/table7_4.csv and DIR/table7_4.md (default DIR: bench/results). --orders: only
//    these orders (Cook's reference is still the random order's); --tables: print each order's
//    s_opt, q_opt and q_inverse per λ.
// Times are wall clock and process CPU (all threads), single run: compare within one run.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/tools/bake/pr_bake.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_depth.h"
#include "generators/bake/priority/priority.h"
#include "generators/species/registry.h"
#include "prune_math.h"

using namespace forest;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kSource = FOREST_SOURCE_DIR;

struct Timer {
  Clock::time_point wall = Clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const { return std::chrono::duration<double>(Clock::now() - wall).count(); }
  double cpu_s() const { return double(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

struct Options {
  std::string model = kSource + "/bench/species/mig_a_50k.toml";
  std::string old_model = kSource + "/scenes/species/broadleaf.toml";
  std::vector<std::string> compare;
  uint32_t views = 6, resolution = 256;
  std::string out = kSource + "/bench/results";
  bool time = true, table = true, variants = false, print_tables = false;
  std::vector<Priority> orders{Priority::random, Priority::density, Priority::orientation, Priority::combined,
                               Priority::layered};
};

Hull hull_of(TreeModel& m) {
  HullParams hp;
  hp.seed = m.meta.value("seed", uint64_t(1));
  Hull h = build_hull(m.leaves, plant_height(m), hp);
  attach_hull(m, h);
  return h;
}

void bake_time(vk::Context& ctx, const Options& o) {
  TreeModel m = generate_from_species(o.model);
  std::printf("bake of %s: %zu leaves, %zu branch triangles, %u views at %u px\n", o.model.c_str(), m.leaves.size(),
              m.branches.indices.size() / 3, o.views, o.resolution);
  Timer all, t;
  Hull h = hull_of(m);
  double hull_s = t.wall_s(), hull_cpu = t.cpu_s();
  t = Timer();
  attach_crown_light(m, h);
  double crown_s = t.wall_s(), crown_cpu = t.cpu_s();
  t = Timer();
  apply_priority(m, h, Priority::combined, m.meta.value("seed", uint64_t(1)));
  double prio_s = t.wall_s(), prio_cpu = t.cpu_s();
  t = Timer();
  PrBakeOptions po;
  po.views = o.views;
  po.resolution = o.resolution;
  PrMeasurement pm = measure_pr_tables(ctx, m, po);
  double pr_s = t.wall_s(), pr_cpu = t.cpu_s();
  const PrBakeStats& st = pm.stats;
  std::printf("  hull                 %7.2f s wall %7.2f s cpu\n", hull_s, hull_cpu);
  std::printf("  crown depths         %7.2f s wall %7.2f s cpu  (kappa %.3f /m)\n", crown_s, crown_cpu,
              m.bake.crown ? double(m.bake.crown->extinction) : 0.0);
  std::printf("  priority (combined)  %7.2f s wall %7.2f s cpu\n", prio_s, prio_cpu);
  std::printf("  PR references        %7.2f s wall  (%u views: full + branch masks)\n", st.reference_seconds, o.views);
  std::printf("  PR renders + counts  %7.2f s wall  (%u pruned renders, %u submits incl. readback)\n",
              st.compare_seconds, st.renders, st.submits);
  std::printf("  PR total             %7.2f s wall %7.2f s cpu\n", pr_s, pr_cpu);
  std::printf("  bake total           %7.2f s wall %7.2f s cpu\n", all.wall_s(), all.cpu_s());
}

void old_vs_new(vk::Context& ctx, const Options& o) {
  TreeModel m = generate_from_species(o.old_model);
  Hull h = hull_of(m);
  apply_priority(m, h, Priority::combined, m.meta.value("seed", uint64_t(1)));
  PrBakeOptions po;
  po.views = o.views;
  po.resolution = o.resolution;
  PrBakeOptions old = po;
  old.batched = false;
  old.search_scale = false;
  Timer t;
  PrMeasurement a = measure_pr_tables(ctx, m, old);
  double old_s = t.wall_s(), old_cpu = t.cpu_s();
  t = Timer();
  PrMeasurement b = measure_pr_tables(ctx, m, po);
  double new_s = t.wall_s(), new_cpu = t.cpu_s();
  float ds = 0, dq = 0, dl = 0;
  for (int i = 0; i < S_SAMPLES; ++i) {
    ds = std::max(ds, std::abs(a.tables.s_opt[i] - b.tables.s_opt[i]) / a.tables.s_opt[i]);
    dq = std::max(dq, std::abs(a.tables.q_opt[i] - b.tables.q_opt[i]));
  }
  for (int j = 0; j < D_SAMPLES; ++j) dl = std::max(dl, std::abs(a.tables.lambda_opt[j] - b.tables.lambda_opt[j]));
  std::printf("PR measurement of %s (%zu leaves), original vs current path:\n", o.old_model.c_str(), m.leaves.size());
  std::printf("  original (1 submit/render, exhaustive s) %7.2f s wall %7.2f s cpu, %u renders\n", old_s, old_cpu,
              a.stats.renders);
  std::printf("  current  (batched, s search)             %7.2f s wall %7.2f s cpu, %u renders\n", new_s, new_cpu,
              b.stats.renders);
  std::printf("  speed-up %.1fx wall, %.1fx cpu; max |ds_opt|/s_opt %.3f, max |dQ_opt| %.4f, max |dlambda_opt| %.3f\n",
              old_s / new_s, old_cpu / new_cpu, double(ds), double(dq), double(dl));
}

// Table 7.4 -------------------------------------------------------------------------------

struct OrderRow {
  std::string model, order;
  std::vector<float> d, lambda_cook, q_cook, lambda_needed;
  double mean_saved = 0, min_saved = 1, max_saved = -1, total_saved = 0;
};

double sample_quality(const PrMeasurement& pm, float l, float s) {
  for (const PrSample& ps : pm.samples)
    if (ps.lambda == l && ps.scale == s) return ps.pr.quality();
  return -1.0;
}

void table_7_4(vk::Context& ctx, const Options& o, const std::string& device) {
  std::vector<std::string> models = o.compare;
  if (models.empty())
    for (const char* n : {"broadleaf", "particle_flow_oak_hero", "mig_a_hero"})
      models.push_back(kSource + "/scenes/species/" + n + ".toml");
  std::vector<OrderRow> rows;
  std::vector<int> ds;  // d_sample indices used: d = 0.1 … 0.9, uniform
  // d = 0.1 … 0.7 (λ_Cook 0.81 … 0.09): below λ = 0.05, the first tabulated detail level,
  // q_opt is interpolated toward Q = 0 at λ = 0 and says nothing about the orders.
  for (int j = 10; j < D_SAMPLES; ++j)
    if (prune::lambda_cook(prune::d_sample(uint32_t(j))) >= 1.0f / float(S_SAMPLES - 1)) ds.push_back(j);
  for (const std::string& file : models) {
    TreeModel base = generate_from_species(file);
    std::string name = std::filesystem::path(file).stem().string();
    Hull h = hull_of(base);
    uint64_t seed = base.meta.value("seed", uint64_t(1));
    PrMeasurement random;
    struct Variant {
      Priority p;
      std::string name;
      PriorityParams params;
    };
    std::vector<Variant> variants;
    for (Priority p : o.orders)
      variants.push_back({p, p == Priority::random ? "random + s_opt (Opt PR)" : std::string(priority_name(p)), {}});
    if (o.variants) {
      PriorityParams greedy;
      greedy.density_uniform_cv = 0.0f;
      greedy.density_random_below = 0.0f;
      variants.push_back({Priority::density, "density, greedy to the end", greedy});
      variants.push_back({Priority::combined, "combined, greedy density", greedy});
    }
    for (const Variant& var : variants) {
      Priority p = var.p;
      TreeModel m = base;
      reorder_leaves(m, priority_order(m, h, p, seed, var.params));
      PrBakeOptions po;
      po.views = o.views;
      po.resolution = o.resolution;
      Timer t;
      PrMeasurement pm = measure_pr_tables(ctx, m, po);
      if (p == Priority::random) random = pm;
      if (o.print_tables) {
        std::printf("  lambda  s_opt  q_opt  q_inverse\n");
        for (int i = 1; i < S_SAMPLES; ++i)
          std::printf("  %.2f  %6.3f  %.4f  %.4f\n", double(pr_lambda(uint32_t(i))), double(pm.tables.s_opt[size_t(i)]),
                      double(pm.tables.q_opt[size_t(i)]), double(pm.tables.q_inverse[size_t(i)]));
      }
      if (random.samples.empty()) {  // Cook's quality comes from the random order's renders
        TreeModel rm = base;
        reorder_leaves(rm, priority_order(rm, h, Priority::random, seed, {}));
        random = measure_pr_tables(ctx, rm, po);
      }
      OrderRow r;
      r.model = name + " (" + std::to_string(m.leaves.size()) + " leaves)";
      r.order = var.name;
      double sum_needed = 0, sum_cook = 0;
      for (int j : ds) {
        float lc = pr_lambda_cook(uint32_t(j));
        double target = sample_quality(random, lc, 1.0f / lc);  // Cook et al.: random order, s = 1/λ
        float need = smallest_lambda_reaching(pm.tables.q_opt, target, 1.0f);
        double saved = 1.0 - double(need) / double(lc);
        r.d.push_back(pr_d(uint32_t(j)));
        r.lambda_cook.push_back(lc);
        r.q_cook.push_back(float(target));
        r.lambda_needed.push_back(need);
        r.mean_saved += saved / double(ds.size());
        r.min_saved = std::min(r.min_saved, saved);
        r.max_saved = std::max(r.max_saved, saved);
        sum_needed += need, sum_cook += lc;
      }
      r.total_saved = 1.0 - sum_needed / sum_cook;
      std::printf("%-34s %-26s saved vs Cook: mean %5.1f %% (min %5.1f, max %5.1f), total %5.1f %%  [%.1f s]\n",
                  r.model.c_str(), r.order.c_str(), 100 * r.mean_saved, 100 * r.min_saved, 100 * r.max_saved,
                  100 * r.total_saved, t.wall_s());
      std::fflush(stdout);
      rows.push_back(std::move(r));
    }
  }

  std::filesystem::create_directories(o.out);
  std::string csv_path = o.out + "/table7_4.csv", md_path = o.out + "/table7_4.md";
  {
    std::ofstream csv(csv_path + ".tmp");
    csv << "model,order,d,lambda_cook,q_cook,lambda_needed,saved\n";
    for (const OrderRow& r : rows)
      for (size_t k = 0; k < r.d.size(); ++k)
        csv << '"' << r.model << "\",\"" << r.order << "\"," << r.d[k] << ',' << r.lambda_cook[k] << ',' << r.q_cook[k]
            << ',' << r.lambda_needed[k] << ',' << 1.0 - double(r.lambda_needed[k]) / double(r.lambda_cook[k]) << '\n';
  }
  std::filesystem::rename(csv_path + ".tmp", csv_path);
  {
    std::ofstream md(md_path + ".tmp");
    md << "# Geometry saved vs Cook et al. at equal PR quality (Neubert 2012 Table 7.4)\n\n"
       << "Device: " << device << ". Coverage " << o.resolution << " px, " << o.views
       << " views, s grid of 12 per λ (searched). Cook et al. = random order, s = 1/λ at λ_Cook(d) = (1 − d)²; "
       << "each order needs the smallest λ whose Q(λ, s_opt(λ)) reaches that quality; saved = 1 − λ/λ_Cook over "
       << "d = 0.1 … 0.7 (mean, min, max; total = 1 − Σλ/Σλ_Cook). Made by `build/bake_bench --skip-time`.\n\n"
       << "| model | order | mean saved | min | max | total saved |\n|---|---|---|---|---|---|\n";
    char buf[256];
    for (const OrderRow& r : rows) {
      std::snprintf(buf, sizeof(buf), "| %s | %s | %.1f %% | %.1f %% | %.1f %% | %.1f %% |\n", r.model.c_str(),
                    r.order.c_str(), 100 * r.mean_saved, 100 * r.min_saved, 100 * r.max_saved, 100 * r.total_saved);
      md << buf;
    }
    md << "| paper (1276 trees, camera path) | Opt PR / density / silhouette / combined | 10.1 / 17.4 / 40.7 / 30.1 % "
          "| 4.3 / 2.2 / 30.8 / 1.4 % | 43.7 / 23.6 / 69.3 / 39.2 % | |\n";
  }
  std::filesystem::rename(md_path + ".tmp", md_path);
  std::printf("wrote %s and %s\n", csv_path.c_str(), md_path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bake_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--model") o.model = value();
    else if (a == "--old-model") o.old_model = value();
    else if (a == "--compare") o.compare.push_back(value());
    else if (a == "--views") o.views = uint32_t(std::stoul(value()));
    else if (a == "--resolution") o.resolution = uint32_t(std::stoul(value()));
    else if (a == "--out") o.out = value();
    else if (a == "--skip-time") o.time = false;
    else if (a == "--skip-compare") o.table = false;
    else if (a == "--variants") o.variants = true;
    else if (a == "--tables") o.print_tables = true;
    else if (a == "--orders") {
      o.orders.clear();
      std::string list = value();
      for (size_t at = 0; at <= list.size();) {
        size_t end = std::min(list.find(',', at), list.size());
        std::optional<Priority> p = parse_priority(list.substr(at, end - at));
        if (!p) {
          std::fprintf(stderr, "bake_bench: unknown order '%s'\n", list.substr(at, end - at).c_str());
          return 2;
        }
        o.orders.push_back(*p);
        at = end + 1;
      }
    }
    else {
      std::fprintf(stderr, "bake_bench: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  vk::Context ctx;
  try {
    vk::create_context(ctx, {});
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(ctx.physical, &props);
    std::string device = std::string(ctx.properties.deviceName) + ", " + driver.driverName + " " + driver.driverInfo;
    std::printf("device: %s\n", device.c_str());
    if (o.time) {
      bake_time(ctx, o);
      old_vs_new(ctx, o);
    }
    if (o.table) table_7_4(ctx, o, device);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bake_bench: %s\n", e.what());
    vk::destroy_context(ctx);
    return 1;
  }
  vk::destroy_context(ctx);
  return 0;
}
