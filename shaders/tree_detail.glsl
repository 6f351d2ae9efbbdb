// How much of a tree the camera's mode draws, shared by cull.comp and shadow_cull.comp so that
// a pruned tree casts its pruned shadow: detail λ and leaf area scale s from the distance of
// the tree's sphere centre to the LOD camera (Neubert 2012 ch7; Cook et al. 2007 for PRUNE_COOK).
// Needs common.glsl.

// s_opt(λ) from the model's table, linearly interpolated.
float opt_area_scale(Model m, float lambda) {
  float spos = clamp(lambda, 0.0, 1.0) * float(S_SAMPLES - 1);
  uint sat = m.table_offset + uint(spos);
  return mix(prune_tables[sat], prune_tables[min(sat + 1, m.table_offset + S_SAMPLES - 1)], fract(spos));
}

void tree_detail(Model m, float camera_distance, out float lambda, out float area_scale) {
  float d = clamp(camera_distance / frame.prune.x, 0.0, 1.0);
  lambda = 1.0;
  area_scale = 1.0;
  if (frame.prune_mode == PRUNE_COOK) {
    lambda = lambda_cook(d);
    area_scale = 1.0 / max(lambda, 1e-3);
  } else if (frame.prune_mode == PRUNE_OPT && m.has_tables != 0) {
    float pos = d_table_position(d);
    uint at = m.table_offset + S_SAMPLES + uint(pos);
    lambda = mix(prune_tables[at], prune_tables[min(at + 1, m.table_offset + TABLE_FLOATS - 1)], fract(pos));
    area_scale = opt_area_scale(m, lambda);
  } else if (frame.prune_mode == PRUNE_FIXED) {
    lambda = frame.prune.z;
    area_scale = frame.prune.w;
  }
}
