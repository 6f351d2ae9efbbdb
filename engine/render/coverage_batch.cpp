// Batched coverage comparisons for the PR bake (Renderer::set_coverage_views and
// compare_coverage). A bake measures a few hundred (λ, s) points from several views; drawn
// one submit each, every render redraws the branches (identical in all of them) and pays a
// queue round trip. Here the branches are drawn once per view into a mask and each pruned
// render draws only its leaf prefix: in coverage mode every fragment writes the same white,
// so the covered pixels of branches + leaves are exactly the union of the two masks, and
// the counts equal those of render_reference + compare_with_reference (tested). The leaves
// go through the lattice pipeline (draw_pass.h), so each render is counted at every PR size.
// Each render goes through Renderer::record_scene, the recording path of frames.
#include <algorithm>
#include <cstring>

#include "engine/render/renderer.h"

namespace forest {

namespace {

// Coverage jobs run strictly one after another; a full barrier between steps keeps the
// recording simple (lavapipe serializes anyway, and a bake is not a frame).
void full_barrier(VkCommandBuffer cmd) {
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

}  // namespace

void Renderer::reserve_coverage(uint32_t reference_frames, uint32_t results) {
  drain();  // the buffers and the sets that bind them may be replaced
  if (reserve_pr_count(ctx_, pr_count_, reference_frames, results)) write_descriptors();
}

void Renderer::record_coverage_render(VkCommandBuffer cmd, const FrameSlot& slot, const gpu::FrameData& frame,
                                      bool branches, bool leaves) {
  DrawList list;
  list.background = false;
  list.lattices = true;
  list.instanced_leaves = (frame.view_flags & VIEW_LEAF_INSTANCED) != 0;
  list.views = draws_a_view(frame.view_flags);
  // The bark once per PR size, each pass at the branch LOD the cull pass picks for a render at
  // that size (pixels per metre 2^b times fewer), then the leaves, all into one attachment.
  const uint32_t bark_passes = branches ? PR_SIZES : 0;
  for (uint32_t pass = 0; pass < bark_passes + (leaves ? 1 : 0); ++pass) {
    const bool bark = pass < bark_passes;
    gpu::FrameData f = frame;
    if (bark) f.lod.x = frame.lod.x / float(1u << pass), f.lod.z = float(pass);
    vkCmdUpdateBuffer(cmd, slot.frame.buffer, 0, sizeof(f), &f);
    full_barrier(cmd);
    list.branches = bark;
    list.leaves = !bark;
    list.keep_color = pass > 0;
    record_scene(cmd, slot, list, false, false);
    full_barrier(cmd);
  }
  vk::image_barrier(cmd, targets_.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
  color_layout_ = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
}

void Renderer::set_coverage_views(const std::vector<CameraDesc>& views) {
  if (targets_.samples != VK_SAMPLE_COUNT_1_BIT || buffers_.instance_count == 0)
    throw vk::VkFailure("coverage batches need a single-sampled renderer with at least one tree");
  const uint32_t count = uint32_t(views.size());
  reserve_coverage(std::max(2 * count, 1u), 1);
  coverage_views_ = views;
  FrameSlot& slot = next_slot();
  vk::begin_commands(slot.cmd);
  for (uint32_t v = 0; v < count; ++v) {
    FrameSettings full;
    full.mask = true;
    gpu::FrameData fd = frame_data(views[v], full);
    // Slot 2v: full detail (relevant pixels); slot 2v + 1: branches only.
    for (int branches_only = 0; branches_only < 2; ++branches_only) {
      record_coverage_render(slot.cmd, slot, fd, true, !branches_only);
      VkBufferImageCopy region{};
      region.bufferOffset = pr_count_.frame_bytes * (2 * v + uint32_t(branches_only));
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {width_, height_, 1};
      vkCmdCopyImageToBuffer(slot.cmd, targets_.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             pr_count_.reference.buffer, 1, &region);
      full_barrier(slot.cmd);
    }
  }
  VK_CHECK(vkEndCommandBuffer(slot.cmd));
  submit(slot);
  wait(slot);
  slot.pending = false;
}

std::vector<PrSizes> Renderer::compare_coverage(const std::vector<CoverageJob>& jobs, std::vector<PrPhases>* phases) {
  std::vector<PrSizes> out(jobs.size());
  if (jobs.empty()) return out;
  for (const CoverageJob& j : jobs)
    if (j.view >= coverage_views_.size()) throw vk::VkFailure("compare_coverage: view without set_coverage_views");
  const uint32_t count = uint32_t(jobs.size());
  const uint32_t stride = PR_SIZES + (phases ? PR_PHASE_BINS : 0u);  // PrCounts per job
  reserve_coverage(1, count * stride);
  const uint32_t pixels = width_ * height_;
  FrameSlot& slot = next_slot();
  vk::begin_commands(slot.cmd);
  vkCmdFillBuffer(slot.cmd, pr_count_.counts.buffer, 0, sizeof(gpu::PrCounts) * count * stride, 0);
  for (uint32_t i = 0; i < count; ++i) {
    const CoverageJob& j = jobs[i];
    FrameSettings test;
    test.mask = true;
    test.prune_mode = PruneMode::fixed;
    test.fixed_lambda = j.lambda;
    test.fixed_scale = j.scale;
    record_coverage_render(slot.cmd, slot, frame_data(coverage_views_[j.view], test), false, true);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(slot.cmd, targets_.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pr_count_.test.buffer, 1,
                           &region);
    full_barrier(slot.cmd);
    vkCmdBindDescriptorSets(slot.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &slot.set, 0, nullptr);
    record_pr_count_pass(slot.cmd, pr_count_, layout_,
                         {pixels, 2 * j.view * pixels, (2 * j.view + 1) * pixels, i * stride, width_, 1u,
                          phases ? i * stride + PR_SIZES : PR_NO_MASK});
    full_barrier(slot.cmd);
  }
  record_pr_readback(slot.cmd, pr_count_, count * stride);
  VK_CHECK(vkEndCommandBuffer(slot.cmd));
  submit(slot);
  wait(slot);
  slot.pending = false;
  std::vector<gpu::PrCounts> counts = read_pr_counts(pr_count_, count * stride);
  if (phases) phases->assign(count, PrPhases(PR_PHASE_BINS));
  for (uint32_t i = 0; i < count; ++i) {
    for (uint32_t b = 0; b < PR_SIZES; ++b) {
      const gpu::PrCounts& c = counts[i * stride + b];
      out[i][b] = {c.tp, c.fp, c.fn};
    }
    for (uint32_t k = 0; phases && k < PR_PHASE_BINS; ++k) {
      const gpu::PrCounts& c = counts[i * stride + PR_SIZES + k];
      (*phases)[i][k] = {c.tp, c.fp, c.fn};
    }
  }
  return out;
}

}  // namespace forest
