// How much of a tree the camera's mode draws, shared by cull.comp and shadow_cull.comp so that
// a pruned tree casts its pruned shadow: detail λ and leaf area scale s from the distance of
// the tree's sphere centre to the LOD camera and the sphere's projected size there (Neubert
// 2012 ch7, its tables measured per size; Cook et al. 2007 for PRUNE_COOK).
// Needs common.glsl.

// Tables of size block b (gpu_types.h): value i of the part at `part`.
float table_value(Model m, uint b, uint part, uint i) {
  return prune_tables[m.table_offset + b * TABLE_BLOCK + part + i];
}

// A part of S_SAMPLES values at λ, linearly interpolated, in block b.
float lambda_table(Model m, uint b, uint part, float lambda) {
  float pos = clamp(lambda, 0.0, 1.0) * float(S_SAMPLES - 1);
  uint i = min(uint(pos), S_SAMPLES - 2);
  return mix(table_value(m, b, part, i), table_value(m, b, part, i + 1), pos - float(i));
}

// The two size blocks around projected size p and the weight of the second.
void size_blocks(Model m, float p, out uint b0, out uint b1, out float w) {
  float pos = size_table_position(p, m.pr_size0);
  b0 = min(uint(pos), PR_SIZES - 1);
  b1 = min(b0 + 1, PR_SIZES - 1);
  w = pos - float(b0);
}

// The first regular λ sample, 1/20: below it the far samples (gpu_types.h).
const float FIRST_LAMBDA = 1.0 / float(S_SAMPLES - 1);

// s_opt(λ, p), bilinear in λ and log2 p. Below the first regular λ (1/20) the far samples
// λ_f = 1/40, 1/80, 1/160 hold the measured s_opt: log s is interpolated in log λ there (s
// stays monotone between monotone samples). Which leaf area a far tree needs depends on the
// model: the area fraction λ·s of 1/20 held constant matched Cook on bench_grove and lost to
// it by 0.016 on fig7_17 (stop 33). Below the last far sample s goes over to Cook's 1/λ,
// continuously: 1/λ · mix(1, λ_F s_F, λ/λ_F), with Cook's clamp λ ≥ 10⁻³ (s ≤ 1000), and the
// drawn leaves never cover more than the crown's n leaves would: s ≤ n / max(λn, 1) (with no
// bound one leaf grew to 10⁶ leaves, larger than its crown: bench_grove's first frame +0.0004
// against +0.007 with the bound). The clamp costs far crowns of many leaves: without it
// fig7_17's worst frame is Q − Q_Cook −0.012 instead of −0.019 (stop 35). But a far crown then
// draws one card of up to n leaves' area, and as it fades in and its λn steps pass, that card
// flips solid blocks: PoppingTest's opt 44 px, beyond its bound of 30 (23 with the clamp).
// The bound is n / max(λn, 1), not n/k with k = ⌈λn⌉, so that s moves as continuously as the
// transition band, which fades by λn too.
float opt_area_scale(Model m, float lambda, float p) {
  uint b0, b1;
  float w;
  size_blocks(m, p, b0, b1, w);
  if (lambda >= FIRST_LAMBDA)
    return mix(lambda_table(m, b0, 0, lambda), lambda_table(m, b1, 0, lambda), w);
  float u = log2(FIRST_LAMBDA / max(lambda, 1e-6));  // 0 at 1/20, f + 1 at far sample f
  uint i = min(uint(u), F_SAMPLES - 1);             // between sample i − 1 (i = 0: 1/20) and i
  float s_near = i == 0u ? mix(table_value(m, b0, 0, 1), table_value(m, b1, 0, 1), w)
                         : mix(table_value(m, b0, TABLE_S_FAR, i - 1), table_value(m, b1, TABLE_S_FAR, i - 1), w);
  float s_far = mix(table_value(m, b0, TABLE_S_FAR, i), table_value(m, b1, TABLE_S_FAR, i), w);
  if (u <= float(F_SAMPLES)) return exp2(mix(log2(s_near), log2(s_far), u - float(i)));
  float last = far_lambda(F_SAMPLES - 1), l = max(lambda, 1e-3);  // s ≤ 1000, as Cook's
  float crown = 1.0 / max(lambda, 1.0 / float(m.leaf_count));  // n / max(λn, 1): continuous
  return min(mix(1.0, last * s_far, l / last) / l, crown);
}

// λ_opt(d, p), bilinear in the d table position and log2 p. Where Cook's λ is below the first
// measured λ (1/20) the tables hold λ_Cook itself (pr_bake.cpp fill_lambda_opt), and between
// their far samples a straight line would lie above the parabola λ_Cook = (1 − d)², up to
// twice Cook's leaves near d = 1 (fig7_17's far frames: 69 % more than Cook): there λ_opt is
// λ_Cook, exactly.
float opt_lambda(Model m, float d, float p) {
  const float cook = lambda_cook(d);
  if (cook < FIRST_LAMBDA) return cook;
  uint b0, b1;
  float w;
  size_blocks(m, p, b0, b1, w);
  float pos = d_table_position(d);
  uint j = min(uint(pos), D_SAMPLES - 2);
  float f = pos - float(j);
  float l0 = mix(table_value(m, b0, TABLE_LAMBDA_OPT, j), table_value(m, b0, TABLE_LAMBDA_OPT, j + 1), f);
  float l1 = mix(table_value(m, b1, TABLE_LAMBDA_OPT, j), table_value(m, b1, TABLE_LAMBDA_OPT, j + 1), f);
  return mix(l0, l1, w);
}

// The smallest λ whose q_opt(λ, p) (bilinear) reaches `quality` and whose q_low, the low
// quantile over views and sub-pixel phases, reaches quality − TARGET_LOW_MARGIN: the first table
// sample, far ones included, where both do, interpolated linearly with the one before; 1 when
// none does. The mean alone left a tenth of single trees 0.1–0.2 under it at 8–16 px. A
// quantile does not interpolate between sizes (a tree at 11 px is not half an 8 px and half a
// 16 px one): the lower of the two size blocks' q_low holds (bench_grove's single trees' 10th
// percentile 0.918 interpolated, 0.930 so).
float target_lambda(Model m, float quality, float p) {
  uint b0, b1;
  float w;
  size_blocks(m, p, b0, b1, w);
  const float low_goal = quality - TARGET_LOW_MARGIN;
  float previous_q = 0.0, previous_low = 0.0, previous_l = 0.0;  // λ = 0: nothing drawn
  for (uint k = 0; k < F_SAMPLES + S_SAMPLES - 1; ++k) {  // ascending λ
    bool far = k < F_SAMPLES;
    uint i = far ? F_SAMPLES - 1 - k : k - F_SAMPLES + 1;
    float l = far ? far_lambda(i) : float(i) * FIRST_LAMBDA;
    uint q_part = far ? TABLE_Q_FAR : TABLE_Q_OPT, low_part = far ? TABLE_Q_LOW_FAR : TABLE_Q_LOW;
    float q = mix(table_value(m, b0, q_part, i), table_value(m, b1, q_part, i), w);
    float low = min(table_value(m, b0, low_part, i), table_value(m, b1, low_part, i));
    if (q >= quality && low >= low_goal) {
      float tq = q > previous_q ? clamp((quality - previous_q) / (q - previous_q), 0.0, 1.0) : 1.0;
      float tl = low > previous_low ? clamp((low_goal - previous_low) / (low - previous_low), 0.0, 1.0) : 1.0;
      return mix(previous_l, l, max(tq, tl));
    }
    previous_q = max(previous_q, q);
    previous_low = max(previous_low, low);
    previous_l = l;
  }
  return 1.0;
}

// `radius`: the instance's bounding sphere (world metres); `camera_distance` to its centre.
void tree_detail(Model m, float radius, float camera_distance, out float lambda, out float area_scale) {
  float d = clamp(camera_distance / frame.prune.x, 0.0, 1.0);
  float p = projected_size(radius, camera_distance, frame.lod.x);
  lambda = 1.0;
  area_scale = 1.0;
  if (frame.prune_mode == PRUNE_COOK) {
    lambda = lambda_cook(d);
    area_scale = 1.0 / max(lambda, 1e-3);
  } else if (frame.prune_mode == PRUNE_OPT && m.has_tables != 0) {
    lambda = opt_lambda(m, d, p);
    area_scale = opt_area_scale(m, lambda, p);
  } else if (frame.prune_mode == PRUNE_TARGET && m.has_tables != 0) {
    lambda = target_lambda(m, frame.prune.z, p);
    area_scale = opt_area_scale(m, lambda, p);
  } else if (frame.prune_mode == PRUNE_FIXED) {
    lambda = frame.prune.z;
    area_scale = frame.prune.w;
  }
}
