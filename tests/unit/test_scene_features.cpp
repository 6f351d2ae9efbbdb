// Scene features without a GPU: camera paths, heightmap terrain, clustered placement and
// the species cache key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "engine/present/image_io.h"
#include "engine/scene/camera_path.h"
#include "engine/scene/heightmap.h"
#include "engine/scene/scene.h"
#include "engine/tools/bake/species_cache.h"
#include "generators/core/input_error.h"
#include "tests/common/test_files.h"
#include "tests/unit/scene_parse.h"

using namespace forest;
using namespace forest::test;
namespace fs = std::filesystem;

namespace {

// A [[path.key]] table: four lines, `extra` keys after them.
std::string path_key(const std::string& time, const std::string& position, const std::string& target,
                     const std::string& extra = "") {
  return "[[path.key]]\ntime = " + time + "\nposition = " + position + "\ntarget = " + target + "\n" + extra;
}

const std::string kPath = "[[path]]\nname = \"walk\"\nfps = 10\n" +
                          path_key("0", "[0, 2, 0]", "[0, 2, 10]") +
                          path_key("2", "[10, 2, 0]", "[10, 2, 10]", "fov = 70\n") +
                          path_key("3", "[10, 4, 10]", "[20, 4, 10]") +
                          path_key("5", "[0, 2, 30]", "[0, 2, 40]");

fs::path temp_dir(const std::string& name) { return fresh_temp_dir("forest_unit", name); }

}  // namespace

TEST(CameraPath, PassesThroughKeysSmoothlyAndClamps) {
  SceneDesc s = parse(kPath);
  ASSERT_EQ(s.paths.size(), 1u);
  const CameraPath* p = find_path(s, "walk");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(find_path(s, "run"), nullptr);
  EXPECT_FLOAT_EQ(p->fps, 10.0f);
  EXPECT_FLOAT_EQ(path_duration(*p), 5.0f);
  for (const CameraKey& k : p->keys) {
    CameraDesc c = camera_at(*p, k.time, s.camera);
    EXPECT_NEAR(glm::distance(c.position, k.position), 0.0f, 1e-4f) << "t = " << k.time;
    EXPECT_NEAR(glm::distance(c.target, k.target), 0.0f, 1e-4f);
    EXPECT_FLOAT_EQ(c.near, s.camera.near);
  }
  EXPECT_FLOAT_EQ(camera_at(*p, 1.0f, s.camera).fov_deg, 60.0f);  // linear fov 50 -> 70
  // Before the first and after the last key: clamped.
  EXPECT_EQ(camera_at(*p, -3.0f, s.camera).position, p->keys.front().position);
  EXPECT_EQ(camera_at(*p, 99.0f, s.camera).position, p->keys.back().position);
  // C0 and bounded speed: no jump anywhere, including across keys.
  float max_step = 0.0f;
  for (float t = 0.0f; t < 5.0f; t += 0.001f)
    max_step = std::max(max_step, glm::distance(camera_at(*p, t, s.camera).position, camera_at(*p, t + 0.001f, s.camera).position));
  EXPECT_LT(max_step, 0.05f);
  // G1 at an interior key: the direction of motion just before ≈ just after key 1 (the
  // speed may change: segments last different times).
  auto direction = [&](float t) {
    return glm::normalize(camera_at(*p, t + 1e-3f, s.camera).position - camera_at(*p, t - 1e-3f, s.camera).position);
  };
  EXPECT_GT(glm::dot(direction(2.0f - 0.005f), direction(2.0f + 0.005f)), 0.99f) << "the path kinks at a key";
}

TEST(CameraPath, CentripetalCatmullRomOnALineIsTheLine) {
  // Equally spaced collinear points: the spline is the segment, traversed monotonically.
  glm::vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0), d(3, 0, 0);
  float last = 0.9f;
  for (float u = 0.0f; u <= 1.0f; u += 0.125f) {
    glm::vec3 p = centripetal_catmull_rom(a, b, c, d, u);
    EXPECT_NEAR(p.y, 0.0f, 1e-6f);
    EXPECT_NEAR(p.x, 1.0f + u, 1e-5f);
    EXPECT_GT(p.x, last);
    last = p.x;
  }
  // Coincident neighbours do not divide by zero.
  glm::vec3 p = centripetal_catmull_rom(b, b, c, c, 0.5f);
  EXPECT_TRUE(std::isfinite(p.x));
  EXPECT_NEAR(p.x, 1.5f, 0.1f);
}

TEST(CameraPath, LoopWrapsTime) {
  SceneDesc s = parse("[[path]]\nname = \"orbit\"\nloop = true\n" + path_key("0", "[10, 5, 0]", "[0, 0, 0]") +
                      path_key("1", "[0, 5, 10]", "[0, 0, 0]") + path_key("2", "[-10, 5, 0]", "[0, 0, 0]") +
                      path_key("3", "[10, 5, 0]", "[0, 0, 0]"));
  const CameraPath& p = s.paths[0];
  for (float t : {0.3f, 1.7f, 2.9f})
    EXPECT_NEAR(glm::distance(camera_at(p, t, s.camera).position, camera_at(p, t + 3.0f, s.camera).position), 0.0f, 1e-3f);
}

TEST(CameraPath, BadPathsNameFileLineAndKey) {
  EXPECT_NE(error_of("[[path]]\nname = \"a\"\n" + path_key("0", "[0,0,0]", "[1,0,0]"))
                .find("path[0].key: a path needs at least 2 keys ([[path.key]] with time, position, target)"),
            std::string::npos);
  std::string two = path_key("1", "[0,0,0]", "[1,0,0]") + path_key("1", "[0,0,1]", "[1,0,0]");
  EXPECT_NE(error_of("[[path]]\nname = \"a\"\n" + two).find("s.toml:8: path[0].key[1].time: must be greater"), std::string::npos)
      << error_of("[[path]]\nname = \"a\"\n" + two);
  EXPECT_NE(error_of("[[path]]\nname = \"a\"\nspeed = 3\n").find("path[0].speed: unknown key"), std::string::npos);
  std::string ok = path_key("0", "[0,0,0]", "[1,0,0]") + path_key("1", "[0,0,1]", "[1,0,0]");
  EXPECT_NE(error_of("[[path]]\nname = \"a\"\n" + ok + "[[path]]\nname = \"a\"\n" + ok).find("already defined"), std::string::npos);
  EXPECT_NE(error_of("[[path]]\nname = \"a\"\n" + path_key("nan", "[0,0,0]", "[1,0,0]") + ok)
                .find("s.toml:4: path[0].key[0].time: must be a finite number"),
            std::string::npos);
}

TEST(Heightmap, SixteenBitPngMapsToTheHeightRangeBilinearly) {
  TerrainDesc d;
  d.heightmap = kScenes + "/heightmaps/valley.png";
  d.size = 256.0f;
  d.resolution = 128;  // one grid vertex per pixel of the 129² map
  d.height = 40.0f;
  d.height_min = -5.0f;
  Heightmap map = read_heightmap(d.heightmap);
  ASSERT_EQ(map.width, 129u);
  // 16 bits survive: far more distinct levels than an 8-bit image could hold.
  std::vector<float> levels = map.values;
  std::sort(levels.begin(), levels.end());
  EXPECT_GT(std::unique(levels.begin(), levels.end()) - levels.begin(), 1000);
  Terrain t = make_terrain(d), again = make_terrain(d);
  EXPECT_EQ(t.heights, again.heights);
  // Grid vertex (i, j) = pixel (i, j): x = -128 + 2i, z = -128 + 2j.
  for (uint32_t j : {0u, 17u, 128u})
    for (uint32_t i : {0u, 64u, 101u})
      EXPECT_NEAR(t.height_at(-128.0f + 2.0f * float(i), -128.0f + 2.0f * float(j)),
                  -5.0f + 40.0f * map.values[size_t(j) * 129 + i], 1e-4f);
  // Between pixels: the bilinear blend of the four.
  float h00 = map.values[size_t(10) * 129 + 20], h10 = map.values[size_t(10) * 129 + 21];
  float h01 = map.values[size_t(11) * 129 + 20], h11 = map.values[size_t(11) * 129 + 21];
  float expect = -5.0f + 40.0f * (0.75f * (0.5f * h00 + 0.5f * h10) + 0.25f * (0.5f * h01 + 0.5f * h11));
  EXPECT_NEAR(t.height_at(-128.0f + 41.0f, -128.0f + 20.5f), expect, 1e-3f);
  auto [lo, hi] = std::minmax_element(t.heights.begin(), t.heights.end());
  EXPECT_GE(*lo, -5.0f);
  EXPECT_LE(*hi, 35.0f);
  EXPECT_GT(*hi - *lo, 20.0f);  // the valley is really there
}

TEST(Heightmap, EightBitImageAndSceneKeys) {
  fs::path dir = temp_dir("heightmap8");
  FrameImage img;
  img.width = 3, img.height = 2;
  img.rgba = {0, 0, 0, 255, 255, 0, 0, 255, 51, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 102, 0, 0, 255};
  write_image(img, dir / "h.png");
  std::ofstream(dir / "s.toml") << "[terrain]\nheightmap = \"h.png\"\nsize = 20\nresolution = 2\nheight = 10\n";
  SceneDesc s = load_scene_file(dir / "s.toml");
  EXPECT_EQ(s.terrain.heightmap, dir / "h.png");
  Terrain t = make_terrain(s.terrain);
  EXPECT_NEAR(t.height_at(0.0f, -10.0f), 10.0f, 1e-4f);   // pixel (1, 0) = 255
  EXPECT_NEAR(t.height_at(10.0f, -10.0f), 2.0f, 1e-4f);   // pixel (2, 0) = 51
  EXPECT_NEAR(t.height_at(10.0f, 10.0f), 4.0f, 1e-4f);    // pixel (2, 1) = 102
  fs::remove_all(dir);
}

TEST(Heightmap, MissingOrCorruptImageIsOneLineInputError) {
  fs::path dir = temp_dir("heightmap_bad");
  std::ofstream(dir / "bad.png") << "\x89PNG\r\n\x1a\n this is not a png";
  std::ofstream(dir / "s.toml") << "[terrain]\nsize = 20\n\nheightmap = \"missing.png\"\n";
  try {
    load_scene_file(dir / "s.toml");
    ADD_FAILURE() << "missing heightmap accepted";
  } catch (const InputError& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("s.toml:4: terrain.heightmap: file not found"), std::string::npos) << m;
  }
  TerrainDesc d;
  d.heightmap = dir / "bad.png";
  try {
    make_terrain(d);
    ADD_FAILURE() << "corrupt heightmap accepted";
  } catch (const InputError& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("bad.png"), std::string::npos) << m;
    EXPECT_NE(m.find("terrain.heightmap"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
  fs::remove_all(dir);
}

namespace {

SceneDesc placement_scene(uint32_t clusters) {
  std::string text = "[terrain]\nsize = 400\nheight = 0\n[[species]]\npreset = \"species/broadleaf.toml\"\n"
                     "[placement]\ncount = 600\nseed = 4\nmin_spacing = 3\nradius = 150\n";
  if (clusters) text += "clusters = " + std::to_string(clusters) + "\ncluster_radius = 8\n";
  return parse(text);
}

// Pairs of trees closer than r: Ripley's K up to a constant, i.e. the integral of the
// pair-correlation function over [0, r].
size_t pairs_within(const std::vector<gpu::Instance>& v, float r) {
  size_t n = 0;
  for (size_t i = 0; i < v.size(); ++i)
    for (size_t j = i + 1; j < v.size(); ++j) {
      glm::vec2 a(v[i].position_scale.x, v[i].position_scale.z), b(v[j].position_scale.x, v[j].position_scale.z);
      n += glm::distance(a, b) < r;
    }
  return n;
}

float min_distance(const std::vector<gpu::Instance>& v) {
  float d = 1e9f;
  for (size_t i = 0; i < v.size(); ++i)
    for (size_t j = i + 1; j < v.size(); ++j)
      d = std::min(d, glm::distance(glm::vec2(v[i].position_scale.x, v[i].position_scale.z),
                                    glm::vec2(v[j].position_scale.x, v[j].position_scale.z)));
  return d;
}

}  // namespace

TEST(Placement, ClustersKeepSpacingAndRaiseShortRangePairCorrelation) {
  SceneDesc uniform = placement_scene(0), clustered = placement_scene(12);
  EXPECT_EQ(clustered.placement.clusters, 12u);
  Terrain t = make_terrain(uniform.terrain);
  uint32_t short_u = 0, short_c = 0;
  std::vector<gpu::Instance> u = place_trees(uniform, t, &short_u), c = place_trees(clustered, t, &short_c);
  ASSERT_EQ(u.size(), 600u);
  ASSERT_EQ(c.size(), 600u) << short_c << " trees found no room";
  EXPECT_GE(min_distance(c), 3.0f - 1e-4f);  // Poisson-disc spacing still holds
  for (const gpu::Instance& i : c) EXPECT_LE(glm::length(glm::vec2(i.position_scale.x, i.position_scale.z)), 150.0f + 1e-3f);
  // Same seed, same forest; another seed, another one.
  std::vector<gpu::Instance> again = place_trees(clustered, t);
  ASSERT_EQ(again.size(), c.size());
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(again[i].position_scale, c[i].position_scale);
  SceneDesc other = placement_scene(12);
  other.placement.seed = 5;
  EXPECT_NE(place_trees(other, t)[0].position_scale, c[0].position_scale);
  // Short range: far more close pairs than uniform (uniform density in the disc gives
  // ≈ N²/2 · πr²/A pairs; 12 clusters of σ = 8 m concentrate the trees).
  size_t pu = pairs_within(u, 10.0f), pc = pairs_within(c, 10.0f);
  EXPECT_GT(pc, 2 * pu) << "clustered " << pc << " vs uniform " << pu;
  // Long range (beyond the clusters) the uniform forest has the relatively more pairs.
  EXPECT_LT(double(pairs_within(c, 150.0f) - pc), double(pairs_within(u, 150.0f) - pu));
}

TEST(SpeciesCache, KeyDependsOnContentSeedAndBakeSettings) {
  fs::path dir = temp_dir("cache_key");
  fs::copy_file(kScenes + "/species/broadleaf.toml", dir / "a.toml");
  SpeciesDesc s;
  s.preset = dir / "a.toml";
  BakeDesc b;
  std::string key = species_cache_key(s, b);
  EXPECT_EQ(key.size(), 32u);
  EXPECT_EQ(key, species_cache_key(s, b));
  // The same content under another name: the same key (content, not path).
  fs::copy_file(dir / "a.toml", dir / "b.toml");
  SpeciesDesc renamed = s;
  renamed.preset = dir / "b.toml";
  EXPECT_EQ(species_cache_key(renamed, b), key);
  SpeciesDesc seeded = s;
  seeded.seed = 5;
  EXPECT_NE(species_cache_key(seeded, b), key);
  seeded.seed = 6;
  EXPECT_NE(species_cache_key(seeded, b), species_cache_key(s, b));
  BakeDesc coarse = b;
  coarse.resolution = 128;
  EXPECT_NE(species_cache_key(s, coarse), key);
  BakeDesc random = b;
  random.priority = "random";
  EXPECT_NE(species_cache_key(s, random), key);
  std::ofstream(dir / "b.toml", std::ios::app) << "\n# one more comment\n";
  EXPECT_NE(species_cache_key(renamed, b), key);

  const char* old = std::getenv("FOREST_CACHE");
  std::string saved = old ? old : "";
  setenv("FOREST_CACHE", (dir / "cache").c_str(), 1);
  EXPECT_EQ(default_cache_dir(), dir / "cache");
  if (old) setenv("FOREST_CACHE", saved.c_str(), 1); else unsetenv("FOREST_CACHE");
  fs::remove_all(dir);
}

TEST(SceneFile, BakeTableAndClusterKeys) {
  SceneDesc s = parse("[bake]\npriority = \"density\"\nviews = 2\nresolution = 64\n");
  EXPECT_EQ(s.bake.priority, "density");
  EXPECT_EQ(s.bake.views, 2u);
  EXPECT_EQ(s.bake.resolution, 64u);
  EXPECT_NE(error_of("[bake]\npriority = \"tallest\"\n").find("bake.priority"), std::string::npos);
  EXPECT_NE(error_of("[placement]\nclusters = -1\n").find("placement.clusters"), std::string::npos);
  EXPECT_NE(error_of("[placement]\ncluster_radius = 0\n").find("placement.cluster_radius"), std::string::npos);
}

TEST(Scene, FullDetailSizeSumsEveryInstance) {
  Scene s;
  TreeModel a, b;
  a.branches.vertices.resize(4);
  a.branches.indices = {0, 1, 2, 2, 1, 3};
  a.leaf_card.vertices.resize(4);
  a.leaf_card.indices = {0, 1, 2, 2, 1, 3};
  a.leaves.resize(3);
  b.branches.vertices.resize(10);
  b.branches.indices.assign(27, 0);  // 9 triangles
  b.branch_lods.push_back({a.branches, 1.0f});  // coarser levels are not full detail
  s.models = {a, b};
  s.instances.resize(3);
  s.instances[0].model = 0, s.instances[1].model = 1, s.instances[2].model = 0;
  FullDetailSize f = full_detail_size(s);
  EXPECT_EQ(f.vertices, 2u * (4 + 3 * 4) + 10u);
  EXPECT_EQ(f.triangles, 2u * (2 + 3 * 2) + 9u);
}

// Issue 6: the benchmark forest has 5000 trees of at least 8 models and more than a billion
// distinct vertices at full detail (generated in-process here, without baking).
TEST(Scene, Forest5000IsOverABillionVerticesAtFullDetail) {
  SceneDesc desc = load_scene_file(std::string(FOREST_SOURCE_DIR) + "/scenes/forest5000.toml");
  Scene scene = build_scene(desc);
  EXPECT_GE(scene.models.size(), 8u);
  EXPECT_EQ(scene.instances.size(), 5000u);
  FullDetailSize full = full_detail_size(scene);
  std::printf("forest5000 at full detail: %llu vertices, %llu triangles\n", (unsigned long long)full.vertices,
              (unsigned long long)full.triangles);
  EXPECT_GE(full.vertices, 1'000'000'000ull);
}
