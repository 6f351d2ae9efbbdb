// Bake timing and the rendering-priority comparison of Neubert 2012 Table 7.4. Usage:
//   bake_bench [--model SPECIES.toml] [--old-model SPECIES.toml] [--compare SPECIES.toml]...
//              [--views N] [--resolution PX] [--out DIR] [--skip-time] [--skip-compare]
//              [--orders random,density,...] [--tables] [--searched MASK]
// 1. Bake time of --model (default bench/species/mig_a_50k.toml, ~62 K leaves) by stage:
//    hull, priority (combined), PR references, PR pruned renders + counts (+ readback); the
//    PR measurement twice in one run: the tables at every projected size (--resolution, default
//    512 px, and its halvings) and the single-size bake of format 1 (256 px, one s search per λ).
// 2. The s search against trying every s on the grid, on --old-model (default
//    scenes/species/broadleaf.toml): renders, and how far the tables moved at each size.
// 3. Table 7.4: for every --compare model (default broadleaf, particle_flow_oak_hero, mig_a_hero)
//    and every priority order, the detail λ needed to match the quality of Cook et al.
//    (random order, s = 1/λ, at λ_Cook(d) = (1 − d)²) with that order's s_opt, along
//    d = 0.1 … 0.7, at each projected size: geometry saved = 1 − λ/λ_Cook. "random" is the
//    paper's "Opt PR" column. Writes DIR/table7_4.csv and DIR/table7_4.md (default DIR:
//    bench/results). --orders: only these orders (Cook's reference is still the random
//    order's); --tables: print each order's s_opt, q_opt and q_inverse per λ and size;
//    --variants: also the paper's orders unstratified, random stratified, and greedy density.
//    Each order's prefix unevenness is printed too (priority_stratify.h: why it matters).
// --searched: the sizes whose s is searched in 1. and 2. (PrBakeOptions::searched_sizes).
// Times are wall clock and process CPU (all threads), single run: compare within one run.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <string>
#include <vector>

#include "engine/tools/bake/pr_bake.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_depth.h"
#include "generators/bake/priority/priority.h"
#include "generators/bake/priority/priority_stratify.h"
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
  uint32_t views = 6, resolution = 512, single_size = 256;
  uint32_t searched_sizes = kSearchedSizes;  // PrBakeOptions::searched_sizes, bit b for size b
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
  po.size0 = o.resolution;
  po.searched_sizes = o.searched_sizes;
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
  std::printf("  PR total             %7.2f s wall %7.2f s cpu  (%u sizes, %u ... %g px across, %u px renders)\n",
              pr_s, pr_cpu, PR_SIZES, o.resolution, double(pr_size(float(o.resolution), PR_SIZES - 1)),
              pr_render_resolution(o.resolution));
  std::printf("  bake total           %7.2f s wall %7.2f s cpu\n", all.wall_s(), all.cpu_s());
  // The single-size bake of format 1 on the same model in the same run: one size, one s
  // search per λ.
  PrBakeOptions single = po;
  single.size0 = o.single_size;
  single.searched_sizes = 1;
  t = Timer();
  PrMeasurement one = measure_pr_tables(ctx, m, single);
  double one_s = t.wall_s(), one_cpu = t.cpu_s();
  std::printf("  single size (%u px)  %7.2f s wall %7.2f s cpu  (%u pruned renders)\n", o.single_size, one_s, one_cpu,
              one.stats.renders);
  std::printf("  per-size tables / single size: %.2fx wall, %.2fx cpu\n", pr_s / one_s, pr_cpu / one_cpu);
}

void old_vs_new(vk::Context& ctx, const Options& o) {
  TreeModel m = generate_from_species(o.old_model);
  Hull h = hull_of(m);
  apply_priority(m, h, Priority::combined, m.meta.value("seed", uint64_t(1)));
  PrBakeOptions po;
  po.views = o.views;
  po.size0 = o.resolution;
  po.searched_sizes = o.searched_sizes;
  PrBakeOptions every = po;
  every.search_scale = false;
  Timer t;
  PrMeasurement a = measure_pr_tables(ctx, m, every);
  double old_s = t.wall_s(), old_cpu = t.cpu_s();
  t = Timer();
  PrMeasurement b = measure_pr_tables(ctx, m, po);
  double new_s = t.wall_s(), new_cpu = t.cpu_s();
  std::printf("PR measurement of %s (%zu leaves), every s on the grid vs the s search:\n", o.old_model.c_str(),
              m.leaves.size());
  std::printf("  every s    %7.2f s wall %7.2f s cpu, %u renders\n", old_s, old_cpu, a.stats.renders);
  std::printf("  s search   %7.2f s wall %7.2f s cpu, %u renders (%.1fx wall)\n", new_s, new_cpu, b.stats.renders,
              old_s / new_s);
  for (uint32_t k = 0; k < PR_SIZES; ++k) {
    const PrSizeTables &x = a.tables.sizes[k], &y = b.tables.sizes[k];
    float ds = 0, dq = 0, dl = 0;
    for (int i = 0; i < S_SAMPLES; ++i) {
      ds = std::max(ds, std::abs(x.s_opt[i] - y.s_opt[i]) / x.s_opt[i]);
      dq = std::max(dq, std::abs(x.q_opt[i] - y.q_opt[i]));
    }
    for (int j = 0; j < D_SAMPLES; ++j) dl = std::max(dl, std::abs(x.lambda_opt[j] - y.lambda_opt[j]));
    std::printf("  %5g px: max |ds_opt|/s_opt %.3f, max |dQ_opt| %.4f, max |dlambda_opt| %.3f\n",
                double(pr_size(a.tables.size0, k)), double(ds), double(dq), double(dl));
  }
}

// Table 7.4 -------------------------------------------------------------------------------

struct OrderRow {
  std::string model, order;
  float size = 0;  // projected size, px across the bounding sphere
  std::vector<float> d, lambda_cook, q_cook, lambda_needed;
  double mean_saved = 0, min_saved = 1, max_saved = -1, total_saved = 0;
};

double sample_quality(const PrMeasurement& pm, float l, float s, uint32_t size) {
  for (const PrSample& ps : pm.samples)
    if (ps.lambda == l && ps.scale == s) return ps.pr[size].quality();
  return -1.0;
}

std::vector<glm::vec3> leaf_centers(const TreeModel& m) {
  std::vector<glm::vec3> c(m.leaves.size());
  for (size_t i = 0; i < c.size(); ++i) c[i] = leaf_center(m.leaves[i]);
  return c;
}

// How unevenly a prefix of λN leaves thins the crown: the variance over cells (edge `cell`)
// of kept − λ·n, divided by the same for a seeded shuffle (≈ λ(1 − λ)·n per cell). 1 = as
// even as random; stratified orders are far below 1, clumping orders above.
double prefix_unevenness(const TreeModel& m, const std::vector<uint32_t>& order, float cell, double lambda,
                         uint64_t seed) {
  std::vector<glm::vec3> centers = leaf_centers(m);
  auto variance = [&](const std::vector<uint32_t>& ord) {
    std::map<std::tuple<int, int, int>, std::pair<double, double>> kept_total;
    const size_t k = size_t(std::ceil(lambda * double(ord.size())));
    for (size_t r = 0; r < ord.size(); ++r) {
      glm::vec3 q = glm::floor(centers[ord[r]] / cell);
      auto& kt = kept_total[{int(q.x), int(q.y), int(q.z)}];
      kt.second += 1.0;
      if (r < k) kt.first += 1.0;
    }
    double v = 0.0;
    for (auto& [id, kt] : kept_total) v += (kt.first - lambda * kt.second) * (kt.first - lambda * kt.second);
    return v / double(kept_total.size());
  };
  Hull none;
  return variance(order) / std::max(1e-12, variance(priority_order(m, none, Priority::random, seed ^ 0x9E37ull)));
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
      bool stratify_random = false;
    };
    std::vector<Variant> variants;
    for (Priority p : o.orders)
      variants.push_back({p, p == Priority::random ? "random + s_opt (Opt PR)" : std::string(priority_name(p)), {}});
    if (o.variants) {
      // The paper's orders as published (unstratified), and Cook's shuffle stratified.
      for (Priority p : o.orders)
        if (p != Priority::random)
          variants.push_back({p, std::string(priority_name(p)) + ", unstratified", PriorityParams{.stratify_cell = 0.0f}});
      variants.push_back({Priority::random, "random, stratified", {}, true});
      PriorityParams greedy;
      greedy.density_uniform_cv = 0.0f;
      greedy.density_random_below = 0.0f;
      variants.push_back({Priority::density, "density, greedy to the end", greedy});
      variants.push_back({Priority::combined, "combined, greedy density", greedy});
    }
    PrBakeOptions po;
    po.views = o.views;
    po.size0 = o.resolution;
    for (const Variant& var : variants) {
      Priority p = var.p;
      TreeModel m = base;
      std::vector<uint32_t> order = priority_order(m, h, p, seed, var.params);
      if (var.stratify_random) order = stratify_order(order, leaf_centers(m), PriorityParams{}.stratify_cell * h.radius, seed);
      std::printf("%-34s %-26s prefix unevenness at lambda 0.3 (cell variance / a shuffle's): %.2f\n", name.c_str(),
                  var.name.c_str(), prefix_unevenness(m, order, PriorityParams{}.stratify_cell * h.radius, 0.3, seed));
      reorder_leaves(m, order);
      Timer t;
      PrMeasurement pm = measure_pr_tables(ctx, m, po);
      if (p == Priority::random) random = pm;
      if (o.print_tables)
        for (uint32_t b = 0; b < PR_SIZES; ++b) {
          const PrSizeTables& st = pm.tables.sizes[b];
          std::printf("  %g px: lambda  s_opt  q_opt  q_inverse\n", double(pr_size(pm.tables.size0, b)));
          for (int i = 1; i < S_SAMPLES; ++i)
            std::printf("  %.2f  %6.3f  %.4f  %.4f\n", double(pr_lambda(uint32_t(i))), double(st.s_opt[size_t(i)]),
                        double(st.q_opt[size_t(i)]), double(st.q_inverse[size_t(i)]));
        }
      if (random.samples.empty()) {  // Cook's quality comes from the random order's renders
        TreeModel rm = base;
        reorder_leaves(rm, priority_order(rm, h, Priority::random, seed, {}));
        random = measure_pr_tables(ctx, rm, po);
      }
      for (uint32_t b = 0; b < PR_SIZES; ++b) {
        OrderRow r;
        r.model = name + " (" + std::to_string(m.leaves.size()) + " leaves)";
        r.order = var.name;
        r.size = pr_size(pm.tables.size0, b);
        double sum_needed = 0, sum_cook = 0;
        for (int j : ds) {
          float lc = pr_lambda_cook(uint32_t(j));
          double target = sample_quality(random, lc, 1.0f / lc, b);  // Cook et al.: random order, s = 1/λ
          float need = smallest_lambda_reaching(pm.tables.sizes[b].q_opt, target, 1.0f);
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
        std::printf("%-34s %-26s %5g px: saved vs Cook: mean %5.1f %% (min %5.1f, max %5.1f), total %5.1f %%\n",
                    r.model.c_str(), r.order.c_str(), double(r.size), 100 * r.mean_saved, 100 * r.min_saved,
                    100 * r.max_saved, 100 * r.total_saved);
        rows.push_back(std::move(r));
      }
      std::printf("  [%.1f s]\n", t.wall_s());
      std::fflush(stdout);
    }
  }

  std::filesystem::create_directories(o.out);
  std::string csv_path = o.out + "/table7_4.csv", md_path = o.out + "/table7_4.md";
  {
    std::ofstream csv(csv_path + ".tmp");
    csv << "model,order,size_px,d,lambda_cook,q_cook,lambda_needed,saved\n";
    for (const OrderRow& r : rows)
      for (size_t k = 0; k < r.d.size(); ++k)
        csv << '"' << r.model << "\",\"" << r.order << "\"," << r.size << ',' << r.d[k] << ',' << r.lambda_cook[k]
            << ',' << r.q_cook[k] << ',' << r.lambda_needed[k] << ','
            << 1.0 - double(r.lambda_needed[k]) / double(r.lambda_cook[k]) << '\n';
  }
  std::filesystem::rename(csv_path + ".tmp", csv_path);
  {
    std::ofstream md(md_path + ".tmp");
    md << "# Geometry saved vs Cook et al. at equal PR quality (Neubert 2012 Table 7.4), per projected size\n\n"
       << "Device: " << device << ". " << o.views << " views, tables at " << PR_SIZES << " projected sizes ("
       << o.resolution << " px across the bounding sphere and its halvings), s grid of 12 per λ (searched). "
       << "Cook et al. = random order, s = 1/λ at λ_Cook(d) = (1 − d)²; each order needs the smallest λ whose "
       << "Q(λ, s_opt(λ)) reaches that quality at the same size; saved = 1 − λ/λ_Cook, mean over d = 0.1 … 0.7. "
       << "Made by `build/bake_bench --skip-time`.\n\n| model | order |";
    for (uint32_t b = 0; b < PR_SIZES; ++b) md << ' ' << pr_size(float(o.resolution), b) << " px |";
    md << " mean of sizes |\n|---|---|";
    for (uint32_t b = 0; b <= PR_SIZES; ++b) md << "---|";
    md << '\n';
    char buf[64];
    for (size_t i = 0; i + PR_SIZES <= rows.size(); i += PR_SIZES) {
      md << "| " << rows[i].model << " | " << rows[i].order << " |";
      double mean = 0;
      for (uint32_t b = 0; b < PR_SIZES; ++b) {
        std::snprintf(buf, sizeof(buf), " %.1f %% |", 100 * rows[i + b].mean_saved);
        md << buf;
        mean += rows[i + b].mean_saved / PR_SIZES;
      }
      std::snprintf(buf, sizeof(buf), " %.1f %% |\n", 100 * mean);
      md << buf;
    }
    md << "\nPaper (1276 trees, camera path): Opt PR 10.1 %, density 17.4 %, silhouette 40.7 %, combined 30.1 % "
          "(mean saved).\n";
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
    else if (a == "--searched") o.searched_sizes = uint32_t(std::stoul(value(), nullptr, 0));
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
