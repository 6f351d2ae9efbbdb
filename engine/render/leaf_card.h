// A leaf card as the renderer draws it: one triangle around the card's quad (leaf_triangle),
// cut back to the quad by the fragment shaders' uv test (tree_frag.glsl, leaf_inside_card).
#pragma once
#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

// The card's corners in the order (0 1 2, 0 2 3) of its two triangles, xy position and uv;
// false unless the card is such a quad: 4 vertices in the plane z = 0 with normal +Z, two
// triangles sharing an edge, wound alike, position and uv one affine map (a parallelogram with
// its texture laid flat).
bool card_quad_corners(const Mesh& card, glm::vec4 out[4]);

// The triangle (xy position, uv; wound as the quad) around the quad q of card_quad_corners.
void leaf_triangle(const glm::vec4 q[4], glm::vec4 out[3]);

}  // namespace forest
