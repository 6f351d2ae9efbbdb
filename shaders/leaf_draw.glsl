// The indirect draw of `count` leaves of model m, shared by cull.comp and shadow_cull.comp:
// leaves [first, first + count) of leaves[] (LEAF_LIST_DIRECT) or of the tail leaf list.
// Pulled (default): one indexed draw of `count` points through the shared pattern's leaf
// points, vertex offset first, so leaf_pulled.vert finds the item at gl_VertexIndex and
// leaf_card.geom makes its triangle; GPUs shade tiny instances with most vertex lanes idle.
// Each leaf is one triangle around its card (gpu_types.h).
// Instanced (VIEW_LEAF_INSTANCED, for the comparison): the same triangle, `count` instances
// from firstInstance = first. `fade`: the mesh's share of a cross-fade with its impostor
// (DrawCommand.fade). Needs common.glsl.
DrawCommand leaf_draw(Model m, uint count, uint first, uint instance, float lambda, float area_scale,
                      float shown_lambda, uint list, float fade) {
  if ((frame.view_flags & VIEW_LEAF_INSTANCED) != 0)
    return DrawCommand(m.card_index_count, count, m.card_first_index, m.card_vertex_offset, first, instance, lambda,
                       area_scale, shown_lambda, list, fade);
  return DrawCommand(LEAF_POINT_INDICES * count, count > 0 ? 1 : 0, m.leaf_quad_first_index + LEAF_QUAD_INDICES,
                     int(first), 0,
                     instance, lambda, area_scale, shown_lambda, list, fade);
}

// The leaf count of a draw made by leaf_draw (tail_cull.comp sets it once the tail is known).
void set_leaf_count(inout DrawCommand d, uint count) {
  if ((frame.view_flags & VIEW_LEAF_INSTANCED) != 0) {
    d.instance_count = count;
  } else {
    d.index_count = LEAF_POINT_INDICES * count;
    d.instance_count = count > 0 ? 1 : 0;
  }
}
