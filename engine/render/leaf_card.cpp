#include "engine/render/leaf_card.h"

namespace forest {

bool card_quad_corners(const Mesh& card, glm::vec4 out[4]) {
  if (card.vertices.size() != 4 || card.indices.size() != 6) return false;
  for (const Vertex& v : card.vertices)
    if (v.position.z != 0.0f || glm::length(v.normal - glm::vec3(0.0f, 0.0f, 1.0f)) > 1e-4f) return false;
  const uint32_t* t1 = &card.indices[0];
  const uint32_t* t2 = &card.indices[3];
  auto in = [](const uint32_t* t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; };
  // Rotate the first triangle so that its corner off the shared edge comes second: (c0, c1, c2);
  // the second triangle must then be (c0, c2, c3) up to rotation.
  int lone = -1;
  for (int k = 0; k < 3; ++k)
    if (!in(t2, t1[k])) lone = k;
  uint32_t fourth = 4;
  for (int k = 0; k < 3; ++k)
    if (!in(t1, t2[k])) fourth = t2[k];
  if (lone < 0 || fourth > 3) return false;
  const uint32_t c[4] = {t1[(lone + 2) % 3], t1[lone], t1[(lone + 1) % 3], fourth};
  bool wound = false;
  for (int r = 0; r < 3; ++r)
    wound = wound || (t2[r] == c[0] && t2[(r + 1) % 3] == c[2] && t2[(r + 2) % 3] == c[3]);
  if (!wound) return false;
  for (int k = 0; k < 4; ++k) {
    const Vertex& v = card.vertices[c[k]];
    out[k] = glm::vec4(v.position.x, v.position.y, v.uv.x, v.uv.y);
  }
  // Position and uv are one affine map of the card plane (a parallelogram with its texture laid
  // flat), as leaf_triangle needs; else its uv would not follow the card's.
  const glm::vec4 opposite = out[1] + out[3] - out[0];
  return glm::length(opposite - out[2]) <= 1e-4f * (1.0f + glm::length(out[2]));
}

// [ours] One triangle around the card quad c0 c1 c2 c3 (c0 c1 its base, c3 c2 the far side):
// the base stretched by half its length at each end, the apex as far beyond the far side as
// the quad is deep. It holds the quad (at the far side it is exactly the quad's width), and
// position and uv extend by the same affine map, so a leaf pixel keeps its uv; the fragment
// shaders drop what lies outside the texture's unit square (leaf_inside_card in
// tree_frag.glsl), so coverage is the quad's. Half the triangles of the quad for twice its area:
// far leaves are sub-pixel, where a triangle costs by count, not by area
// (bench/results/leaf_triangles.md).
void leaf_triangle(const glm::vec4 q[4], glm::vec4 out[3]) {
  const glm::vec4 base = q[1] - q[0], depth = q[3] - q[0];
  out[0] = q[0] - 0.5f * base;
  out[1] = q[1] + 0.5f * base;
  out[2] = 0.5f * (q[2] + q[3]) + depth;
}

}  // namespace forest
