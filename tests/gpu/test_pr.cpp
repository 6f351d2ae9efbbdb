// PR measurement on the GPU (Neubert 2012 §7.2) and the pruning tables measured with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/tools/gallery/contact_sheet.h"
#include "engine/tools/bake/pr_bake.h"
#include "generators/species/registry.h"
#include "prune_math.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

class PrTest : public ValidatedGpuTest {};

}  // namespace

TEST_F(PrTest, CountsMatchTheCpuOnReadBackMasks) {
  TreeModel m = broadleaf();
  Scene scene = make_model_scene(m, 96, 1);
  Renderer r(ctx_, scene, 96, 96, 1);
  CameraDesc cam = orbit_camera(m.bounding_sphere, 0.7f, 0.2f, 30.0f);
  FrameSettings full, pruned;
  pruned.prune_mode = PruneMode::fixed;
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
  const PrBakeOptions o{.size0 = 128, .views = 4, .scale_candidates = 8};
  PrMeasurement pm = measure_pr_tables(ctx_, m, o);
  ASSERT_EQ(pm.tables.sizes.size(), size_t(PR_SIZES));
  EXPECT_EQ(pm.tables.size0, 128.0f);
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    SCOPED_TRACE("size " + std::to_string(b));
    const PrSizeTables& t = pm.tables.sizes[b];
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
    // The far samples below λ = 1/20 are measured like the others: at least Cook's Q, s not
    // growing with λ across them and on into the regular samples.
    ASSERT_EQ(t.s_far.size(), size_t(F_SAMPLES));
    for (int f = 0; f < F_SAMPLES; ++f) {
      SCOPED_TRACE("far " + std::to_string(f));
      EXPECT_GE(t.q_far[f] + 1e-6f, t.q_inverse_far[f]);
      EXPECT_GE(t.s_far[f] + 1e-6f, f == 0 ? t.s_opt[1] : t.s_far[f - 1]);
      EXPECT_LE(t.q_far[f], (f == 0 ? t.q_opt[1] : t.q_far[f - 1]) + (b < 4 ? 0.03f : 0.08f)) << "fewer leaves, less Q";
      EXPECT_GT(t.q_inverse_far[f], 0.0f) << "Cook's point at λ_f was measured";
      EXPECT_LE(t.q_low_far[f], t.q_far[f] + 0.05f);
    }
    // The low quantile of single renders: under the pooled Q (allowing the cross-fitting's
    // noise), 1 at full detail, and rising with λ.
    for (int i = 1; i < S_SAMPLES; ++i) EXPECT_LE(t.q_low[i], t.q_opt[i] + 0.05f) << i;
    EXPECT_FLOAT_EQ(t.q_low[S_SAMPLES - 1], 1.0f);
    EXPECT_GT(t.q_low[S_SAMPLES / 2], t.q_low[1]);
    if (b >= 3) EXPECT_LT(t.q_low[4], t.q_opt[4] - 0.01f) << "single small trees spread below their mean";
    // PR points move toward (1, 1) as λ grows (quality at s_opt, allowing measurement noise,
    // which grows as the tree shrinks to a few pixels).
    for (int i = 2; i < S_SAMPLES; ++i) EXPECT_GE(t.q_opt[i], t.q_opt[i - 1] - (b < 4 ? 0.03f : 0.08f)) << i;
    EXPECT_GT(t.q_opt[S_SAMPLES - 1], 0.999f);
    if (b < 4) EXPECT_LT(t.q_opt[2], 0.95f) << "λ = 0.1 should visibly lose quality";
    // λ_opt never exceeds Cook's λ at the same distance, and never grows with distance.
    for (int j = 0; j < D_SAMPLES; ++j) {
      EXPECT_LE(t.lambda_opt[j], pr_lambda_cook(uint32_t(j)) + 1e-6f) << j;
      if (j > 0) {
        EXPECT_LE(t.lambda_opt[j], t.lambda_opt[j - 1] + 1e-6f) << j;
      }
    }
    EXPECT_FLOAT_EQ(t.lambda_opt[0], 1.0f);
  }
}

TEST_F(PrTest, EachLatticeCountsWhatARenderAtItsSizeCounts) {
  // One bake render counts every PR size: size b at the pixels whose channel holds it
  // (prune::lattice_size), each of them the sample point of a render at 2^-b the resolution
  // at one sub-pixel phase, with the leaf texture read b mip levels coarser. Those renders,
  // made for real (another renderer, the camera shifted to each phase), summed over the
  // phases, count the same pixels. At 8 px (1024 phases, all of them in the alpha channel) a
  // regular 64 of them stand for all, within what they sample.
  TreeModel m = broadleaf();
  const uint32_t R = 256;
  Scene scene = make_model_scene(m, R, 1);
  Renderer r(ctx_, scene, R, R, 1);
  CameraDesc cam = pr_view_camera(m.bounding_sphere, 0.7f, 0.2f, R - 4, R);
  r.set_coverage_views({cam});
  const std::vector<CoverageJob> jobs = {{0, 0.3f, 2.5f}, {0, 0.1f, 6.0f}};
  std::vector<PrPhases> phase_counts;
  std::vector<PrSizes> lattice = r.compare_coverage(jobs, &phase_counts);
  ASSERT_EQ(phase_counts.size(), jobs.size());
  for (uint32_t b = 1; b < PR_SIZES; ++b) {
    const uint32_t low = R >> b, cell = 1u << b, stride = b == 5 ? 4u : 1u;
    Scene small = make_model_scene(m, low, 1);
    Renderer rs(ctx_, small, low, low, 1);
    std::vector<PrResult> real(jobs.size());
    uint32_t phases = 0;
    std::vector<uint64_t> worst(jobs.size(), 0), covered(jobs.size(), 0);  // per phase: |lattice − render|
    for (uint32_t py = 0; py < cell; py += stride)
      for (uint32_t px = 0; px < cell; px += stride) {
        const uint32_t parity = prune::pixel_parity(px, py);
        bool counted = false;
        for (uint32_t c = 1; c < 4; ++c) counted = counted || prune::lattice_size(c, parity) == b;
        if (!counted) continue;
        ++phases;
        // Full-resolution pixel px of a cell of 2^b is the low render's sample point when the
        // image moves by (2^(b-1) - px - 1/2) full pixels.
        CameraDesc shifted = cam;
        shifted.ndc_offset = glm::vec2(float(cell / 2) - float(px) - 0.5f, float(cell / 2) - float(py) - 0.5f) *
                             (2.0f / float(R));
        FrameSettings full;
        rs.render_reference(shifted, full);
        for (size_t k = 0; k < jobs.size(); ++k) {
          FrameSettings test;
          test.prune_mode = PruneMode::fixed;
          test.fixed_lambda = jobs[k].lambda;
          test.fixed_scale = jobs[k].scale;
          PrResult one = rs.compare_with_reference(shifted, test);
          real[k] += one;
          // The phase's own bin counts that one render.
          const PrResult& bin = phase_counts[k][prune::phase_bin(b, px, py)];
          auto diff = [](uint64_t x, uint64_t y) { return x > y ? x - y : y - x; };
          worst[k] = std::max(worst[k], diff(bin.tp, one.tp) + diff(bin.fp, one.fp) + diff(bin.fn, one.fn));
          covered[k] = std::max(covered[k], one.tp + one.fn);
        }
      }
    for (size_t k = 0; k < jobs.size(); ++k) {
      SCOPED_TRACE("size " + std::to_string(low) + " px, job " + std::to_string(k));
      const PrResult& l = lattice[k][b];
      std::printf("%3u px, job %zu: per phase at most %llu pixels apart (of up to %llu covered)\n", low, k,
                  (unsigned long long)worst[k], (unsigned long long)covered[k]);
      EXPECT_LE(double(worst[k]), 0.01 * double(covered[k]) + 3.0) << "a phase bin is not its phase's render";
      if (stride > 1) {  // a sample of the phases: its fractions and Q, not its counts
        const double n = double(real[k].tp + real[k].fn), ln = double(l.tp + l.fn);
        std::printf("%3u px, %4u of %u phases, job %zu: lattice Q %.4f, renders Q %.4f, covered %.4f vs %.4f of a phase\n",
                    low, phases, cell * cell, k, l.quality(), real[k].quality(), ln / double(cell * cell), n / phases);
        EXPECT_NEAR(ln / double(cell * cell), n / double(phases), 0.03 * n / double(phases));
        EXPECT_NEAR(l.quality(), real[k].quality(), 0.02);
        continue;
      }
      const double pixels = double(real[k].tp + real[k].fn);
      EXPECT_GT(pixels, 400.0) << "the phases together see many pixels";
      // A pixel may differ where an edge passes through a sample point (vertices snap to the
      // sub-pixel grid of each resolution). Read at the fine mip instead, the lattices of
      // sub-pixel leaves measured Q 0.043 too high at 16 px.
      const double slack = 0.01 * pixels + 2.0;
      std::printf("%3u px, %4u phases, job %zu: lattice tp %llu fp %llu fn %llu Q %.4f, renders tp %llu fp %llu fn %llu Q %.4f\n",
                  low, phases, k, (unsigned long long)l.tp, (unsigned long long)l.fp, (unsigned long long)l.fn,
                  l.quality(), (unsigned long long)real[k].tp, (unsigned long long)real[k].fp,
                  (unsigned long long)real[k].fn, real[k].quality());
      EXPECT_NEAR(double(l.tp + l.fn), pixels, slack) << "full-detail coverage";
      EXPECT_NEAR(double(l.tp), double(real[k].tp), slack);
      EXPECT_NEAR(double(l.fp), double(real[k].fp), slack);
      EXPECT_NEAR(double(l.fn), double(real[k].fn), slack);
      EXPECT_NEAR(l.quality(), real[k].quality(), 0.005);
    }
  }
}

TEST_F(PrTest, QualityNearlyIndependentOfPixelSize) {
  // Elements several pixels wide at both sizes: what is counted is per pixel, so halving
  // the pixel size changes nothing. (Botanical foliage, sub-pixel at 96 px, is another
  // matter: its PR does depend on projected size, which is what [4/6]'s per-size tables
  // are for.)
  TreeModel m = coarse_broadleaf();
  Scene big = make_model_scene(m, 192, 1), small = make_model_scene(m, 96, 1);
  Renderer rb(ctx_, big, 192, 192, 1), rs(ctx_, small, 96, 96, 1);
  FrameSettings full, pruned;
  pruned.prune_mode = PruneMode::fixed;
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

TEST_F(PrTest, BatchedCountsEqualOneRenderPerSubmit) {
  // Branches drawn once per view and OR-ed in must give exactly the counts of redrawing
  // the whole model for every (λ, s).
  TreeModel m = broadleaf();
  Scene scene = make_model_scene(m, 96, 1);
  Renderer r(ctx_, scene, 96, 96, 1);
  std::vector<CameraDesc> cams = {orbit_camera(m.bounding_sphere, 0.3f, 0.2f, 30.0f),
                                  orbit_camera(m.bounding_sphere, 2.4f, 0.6f, 30.0f)};
  std::vector<CoverageJob> jobs = {{0, 0.3f, 2.0f}, {1, 0.3f, 2.0f}, {1, 0.05f, 9.0f}, {0, 1.0f, 1.0f}, {0, 0.7f, 1.2f}};
  r.set_coverage_views(cams);
  std::vector<PrSizes> lattices = r.compare_coverage(jobs);
  std::vector<PrResult> batched;
  for (const PrSizes& l : lattices) batched.push_back(l[0]);  // size 0: every pixel
  ASSERT_EQ(batched.size(), jobs.size());
  for (size_t i = 0; i < jobs.size(); ++i) {
    SCOPED_TRACE(i);
    FrameSettings full, test;
    test.prune_mode = PruneMode::fixed;
    test.fixed_lambda = jobs[i].lambda;
    test.fixed_scale = jobs[i].scale;
    r.render_reference(cams[jobs[i].view], full);
    PrResult one = r.compare_with_reference(cams[jobs[i].view], test);
    EXPECT_EQ(batched[i].tp, one.tp);
    EXPECT_EQ(batched[i].fp, one.fp);
    EXPECT_EQ(batched[i].fn, one.fn);
    EXPECT_GT(one.tp, 300u);
  }
  EXPECT_EQ(batched[3].fp + batched[3].fn, 0u) << "full detail must match its reference";
  EXPECT_GT(batched[2].fn + batched[2].fp, batched[0].fn + batched[0].fp) << "λ = 0.05 should lose more than λ = 0.3";
}

TEST_F(PrTest, ScaleSearchFindsTheExhaustiveOptimum) {
  // At every size of 16 px and more the bracket search's tables stay within 0.005 in Q of
  // trying every s (below, two views of a tree a few pixels across are mostly noise).
  TreeModel m = broadleaf();
  PrBakeOptions o{.size0 = 256, .views = 2, .scale_candidates = 12, .search_scale = false};
  PrMeasurement all = measure_pr_tables(ctx_, m, o);
  o.search_scale = true;
  PrMeasurement found = measure_pr_tables(ctx_, m, o);
  // The raw argmax per λ (before the tables are made monotone), as an index on the s grid.
  auto best_index = [&](const PrMeasurement& pm, float l, uint32_t b) {
    std::vector<float> grid = scale_grid(l, o.scale_candidates);
    double best = -2.0;
    float s_best = 0.0f;
    for (const PrSample& ps : pm.samples) {
      double q = ps.pr[b].quality();
      if (ps.lambda == l && (q > best || (q == best && ps.scale < s_best))) best = q, s_best = ps.scale;
    }
    return int(std::find(grid.begin(), grid.end(), s_best) - grid.begin());
  };
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    SCOPED_TRACE("size " + std::to_string(b));
    int same = 0;
    for (int i = 1; i < S_SAMPLES; ++i) {
      float l = float(i) / float(S_SAMPLES - 1);
      SCOPED_TRACE(l);
      same += best_index(all, l, b) == best_index(found, l, b);
      EXPECT_NEAR(found.tables.sizes[b].q_opt[i], all.tables.sizes[b].q_opt[i],
                  pr_size(256.0f, b) >= 16.0f ? 0.005f : 0.03f);
    }
    if (pr_size(256.0f, b) >= 16.0f) EXPECT_GE(same, S_SAMPLES - 6) << "the search should usually land on the very same grid value";
    for (int j = 0; j < D_SAMPLES; ++j)
      EXPECT_NEAR(found.tables.sizes[b].lambda_opt[j], all.tables.sizes[b].lambda_opt[j], 0.03f) << j;
  }
  // The sizes' searches share the renders (each counts every size), and together still probe
  // fewer points than the grid holds.
  EXPECT_LT(found.stats.renders, all.stats.renders * 9 / 10) << found.samples.size() << " vs " << all.samples.size();
}

TEST(PrMath, NonIncreasingIsTheLeastSquaresProjection) {
  EXPECT_EQ(non_increasing({3, 2, 1}), (std::vector<float>{3, 2, 1}));
  EXPECT_EQ(non_increasing({1, 3}), (std::vector<float>{2, 2}));
  EXPECT_EQ(non_increasing({5, 1, 3, 0}), (std::vector<float>{5, 2, 2, 0}));
}
