// Bark uv of a junction surface (junction.h): the triangles that join the cut rings at a fork
// get uv at the bark's physical scale, continuing the through branch's tubes where they can.
//
// A junction is a saddle: no one chart maps it without stretch, and its rings carry the
// unrelated u of their tubes. So each triangle gets uv of its own (the mesher gives the
// junction vertex copies of its own): a triangle whose corners are all on the rings of the
// branch passing through the fork (the incoming and the continuing tube, whose u agree: the
// continuation's frame is carried across the fork) takes those tubes' uv, unwrapped to one
// side of their seam, when they stretch it by at most `tolerance`; every other triangle is
// placed across an edge from a neighbour already placed (breadth-first from the tubes'
// triangles), so it continues that neighbour's bark: its third corner keeps the uv it
// already has (or its tube's) where the triangle then stretches by at most `tolerance`, else
// it is unfolded isometrically. Where the unfolding paths meet, and at the side branches'
// rings, the texture is discontinuous.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct JunctionUvCorner {
  uint32_t vertex = 0;      // the ring vertex it copies (shared corners have the same one)
  glm::vec3 position{0.0f};
  bool on_tube = false;     // on the incoming or continuing tube's ring: tube_uv is its uv
  glm::vec2 tube_uv{0.0f};
  float period = 0.0f;      // that ring's u period (tiles): a whole turn around it
};

// Triangles counter-clockwise seen from outside, like the tubes' (whose uv run clockwise:
// v decreases toward the tip); uv in tiles of `tile` metres. One uv per corner.
std::vector<std::array<glm::vec2, 3>> junction_uvs(std::span<const std::array<JunctionUvCorner, 3>> triangles,
                                                   float tile, float tolerance = 0.2f);

}  // namespace forest
