// Mesh or impostor, chosen by PR (cull.comp, shadow_cull.comp): the bake measured the
// impostor's Q against full detail at every PR table size (Model.impostor_q) as it measured
// the mesh's q_opt(λ, p); a tree shows its impostor where that Q reaches what its mesh would
// show at the mode's λ and the tree's projected size, so switching never costs quality
// against the mode, and a mode that keeps more detail (a larger λ, a closer tree) keeps its
// mesh longer. Needs common.glsl and tree_detail.glsl.

// Q of the mesh at detail λ with s_opt, at projected size p: q_opt(λ, p), bilinear.
float mesh_quality(Model m, float lambda, float p) {
  uint b0, b1;
  float w;
  size_blocks(m, p, b0, b1, w);
  return mix(lambda_table(m, b0, TABLE_Q_OPT, lambda), lambda_table(m, b1, TABLE_Q_OPT, lambda), w);
}

// Q of the impostor at projected size p, linear in log2 p between the table sizes.
float impostor_quality(Model m, float p) {
  uint b0, b1;
  float w;
  size_blocks(m, p, b0, b1, w);
  return mix(m.impostor_q[b0], m.impostor_q[b1], w);
}

// Fraction of the tree's pixels its impostor draws, the rest its mesh (a dithered cross-fade
// over IMPOSTOR_FADE_BAND of Q): 0 mesh alone, 1 impostor alone.
float impostor_weight(Model m, float lambda, float p) {
  if (frame.impostors == IMPOSTORS_OFF || m.impostor_layer == 0u) return 0.0;
  if (frame.impostors == IMPOSTORS_ALWAYS) return 1.0;
  if (m.has_tables == 0u) return 0.0;
  return clamp((impostor_quality(m, p) - mesh_quality(m, lambda, p)) / IMPOSTOR_FADE_BAND, 0.0, 1.0);
}
