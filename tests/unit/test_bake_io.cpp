// Baked assets: hull mesh and PR tables survive the .glb round trip; malformed tables fail.
#include <gtest/gtest.h>

#include "generators/asset/asset_io.h"
#include "generators/bake/hull/hull.h"
#include "generators/asset/pr_tables.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"

using namespace forest;

TEST(BakeIo, HullAndTablesRoundTrip) {
  TreeModel m = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/conifer.toml");
  Hull h = build_hull(m.leaves, plant_height(m));
  attach_hull(m, h);
  ASSERT_FALSE(m.hull.indices.empty());
  PrTables t;
  t.lambda.assign(S_SAMPLES, 0.5f);
  t.s_opt.assign(S_SAMPLES, 2.0f);
  t.q_opt.assign(S_SAMPLES, 0.9f);
  t.q_inverse.assign(S_SAMPLES, 0.8f);
  t.d.assign(D_SAMPLES, 0.1f);
  t.lambda_opt.assign(D_SAMPLES, 0.25f);
  t.lambda_cook.assign(D_SAMPLES, 0.3f);
  t.priority = "combined";
  m.meta["pr_tables"] = to_json(t);
  std::vector<uint8_t> bytes = encode_glb(m);
  TreeModel back = decode_glb(bytes, "x.glb");
  EXPECT_EQ(back.hull.indices, m.hull.indices);
  ASSERT_EQ(back.hull.vertices.size(), m.hull.vertices.size());
  for (size_t i = 0; i < m.hull.vertices.size(); ++i)
    ASSERT_EQ(back.hull.vertices[i].position, m.hull.vertices[i].position);
  auto tables = read_pr_tables(back.meta, "x.glb");
  ASSERT_TRUE(tables.has_value());
  EXPECT_EQ(tables->s_opt, t.s_opt);
  EXPECT_EQ(tables->lambda_opt, t.lambda_opt);
  EXPECT_EQ(tables->priority, "combined");
  EXPECT_EQ(back.meta["hull_samples"].size(), h.samples.size());
}

TEST(BakeIo, MalformedTablesNameTheKey) {
  nlohmann::json meta = {{"pr_tables", {{"lambda", {0.1, 0.2}}}}};
  try {
    read_pr_tables(meta, "m.glb");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.glb"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("pr_tables.lambda"), std::string::npos);
  }
  EXPECT_FALSE(read_pr_tables(nlohmann::json::object(), "m.glb").has_value());
}
