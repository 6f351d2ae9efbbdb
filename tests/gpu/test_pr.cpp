// PR measurement on the GPU (seed 000 §7.2) and the pruning tables measured with it.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/contact_sheet.h"
#include "engine/render/pr_bake.h"
#include "generators/methods/methods.h"

using namespace forest;

namespace {

const std::string kSource = FOREST_SOURCE_DIR;

class PrTest : public ::testing::Test {
 protected:
  void SetUp() override {
    vk::ContextOptions options;
    options.validation = true;
    vk::create_context(ctx_, options);
  }
  void TearDown() override {
    vk::destroy_context(ctx_);
    EXPECT_EQ(ctx_.validation_messages.load(), 0u) << "last: " << ctx_.last_validation_message;
  }
  vk::Context ctx_;
};

TreeModel broadleaf() { return generate_from_species(kSource + "/scenes/species/broadleaf.toml", GenerateOptions{11}); }

}  // namespace

TEST_F(PrTest, CountsMatchTheCpuOnReadBackMasks) {
  TreeModel m = broadleaf();
  Scene scene = make_model_scene(m, 96, 1);
  Renderer r(ctx_, scene, 96, 96, 1);
  CameraDesc cam = orbit_camera(m.bounding_sphere, 0.7f, 0.2f, 30.0f);
  FrameSettings full, pruned;
  pruned.prune_mode = PRUNE_FIXED;
  pruned.fixed_lambda = 0.3f;
  pruned.fixed_scale = 2.0f;
  r.render_reference(cam, full);
  PrResult same = r.compare_with_reference(cam, full);
  EXPECT_GT(same.tp, 500u);
  EXPECT_EQ(same.fp, 0u);
  EXPECT_EQ(same.fn, 0u);
  EXPECT_DOUBLE_EQ(same.quality(), 1.0);

  PrResult gpu = r.compare_with_reference(cam, pruned);
  // The same two coverages read back and counted on the CPU.
  FrameImage a, b;
  full.mask = pruned.mask = true;
  r.render(cam, &a, full);
  r.render(cam, &b, pruned);
  uint64_t tp = 0, fp = 0, fn = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    bool rel = a.rgba[i] > 127, ret = b.rgba[i] > 127;
    tp += rel && ret, fp += ret && !rel, fn += rel && !ret;
  }
  EXPECT_EQ(gpu.tp, tp);
  EXPECT_EQ(gpu.fp, fp);
  EXPECT_EQ(gpu.fn, fn);
  EXPECT_GT(fp + fn, 0u) << "pruning to 30% changed no pixel";
}

TEST_F(PrTest, TablesHaveThePaperProperties) {
  TreeModel m = broadleaf();
  PrBakeOptions o;
  o.resolution = 128;
  o.views = 4;
  o.scale_candidates = 8;
  PrMeasurement pm = measure_pr_tables(ctx_, m, o);
  const PrTables& t = pm.tables;
  ASSERT_EQ(t.s_opt.size(), size_t(S_SAMPLES));
  ASSERT_EQ(t.lambda_opt.size(), size_t(D_SAMPLES));
  for (int i = 1; i < S_SAMPLES; ++i) {
    SCOPED_TRACE(i);
    // (7.6): the optimal scale is at least as good as Cook's area preservation s = 1/λ.
    EXPECT_GE(t.q_opt[i] + 1e-6f, t.q_inverse[i]);
    EXPECT_GE(t.s_opt[i], 1.0f);
    EXPECT_LE(t.s_opt[i], t.s_opt[i - 1] + 1e-6f) << "s_opt must not grow with λ";
  }
  EXPECT_FLOAT_EQ(t.s_opt[S_SAMPLES - 1], 1.0f);
  // PR points move toward (1, 1) as λ grows (quality at s_opt, allowing measurement noise).
  for (int i = 2; i < S_SAMPLES; ++i) EXPECT_GE(t.q_opt[i], t.q_opt[i - 1] - 0.03f) << i;
  EXPECT_GT(t.q_opt[S_SAMPLES - 1], 0.999f);
  EXPECT_LT(t.q_opt[2], 0.95f) << "λ = 0.1 should visibly lose quality";
  // λ_opt never exceeds Cook's λ at the same distance, and never grows with distance.
  for (int j = 0; j < D_SAMPLES; ++j) {
    EXPECT_LE(t.lambda_opt[j], t.lambda_cook[j] + 1e-6f) << j;
    if (j > 0) EXPECT_LE(t.lambda_opt[j], t.lambda_opt[j - 1] + 1e-6f) << j;
  }
  EXPECT_FLOAT_EQ(t.lambda_opt[0], 1.0f);
}

TEST_F(PrTest, QualityNearlyIndependentOfPixelSize) {
  TreeModel m = broadleaf();
  Scene big = make_model_scene(m, 192, 1), small = make_model_scene(m, 96, 1);
  Renderer rb(ctx_, big, 192, 192, 1), rs(ctx_, small, 96, 96, 1);
  FrameSettings full, pruned;
  pruned.prune_mode = PRUNE_FIXED;
  pruned.fixed_lambda = 0.4f;
  pruned.fixed_scale = 1.8f;
  PrResult qb, qs;
  for (int v = 0; v < 4; ++v) {
    CameraDesc cam = orbit_camera(m.bounding_sphere, 1.57f * float(v), 0.2f, 30.0f);
    rb.render_reference(cam, full);
    rs.render_reference(cam, full);
    qb += rb.compare_with_reference(cam, pruned);
    qs += rs.compare_with_reference(cam, pruned);
  }
  EXPECT_NEAR(qb.precision(), qs.precision(), 0.05);
  EXPECT_NEAR(qb.recall(), qs.recall(), 0.05);
}

TEST(PrMath, NonIncreasingIsTheLeastSquaresProjection) {
  EXPECT_EQ(non_increasing({3, 2, 1}), (std::vector<float>{3, 2, 1}));
  EXPECT_EQ(non_increasing({1, 3}), (std::vector<float>{2, 2}));
  EXPECT_EQ(non_increasing({5, 1, 3, 0}), (std::vector<float>{5, 2, 2, 0}));
}
