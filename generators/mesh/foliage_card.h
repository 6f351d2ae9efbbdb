// The card that one foliage element is drawn with, and its alpha-masked texture, generated
// from the leaf model (leaf_texture.h). Either a single leaf, or a whole shoot: a twig
// carrying several leaves (or, for conifers, several needle shoots) in the species'
// phyllotaxis, as production tree tools draw foliage (twig-cluster cards). Pure functions of
// the design: no randomness, same design, same bytes.
#pragma once
#include <cstdint>

#include "generators/mesh/leaf_texture.h"
#include "generators/model/tree_model.h"
#include "generators/tree/leaves.h"

namespace forest {

struct ShootDesign {
  bool single_leaf = false;    // true: the card is one leaf (leaf_texture.h's card)
  LeafShape leaf_shape = LeafShape::ovate;
  Phyllotaxis phyllotaxis = Phyllotaxis::alternate;  // of the leaves along the shoot's twig
  int leaves = 6;              // leaves (or needle shoots) on the shoot, the terminal one included
  float leaf_length = 0.35f;   // blade length ÷ shoot length
  float leaf_angle_deg = 50.0f;  // between the twig and a blade
};

// Card width ÷ card length (the length is the element's scale: the shoot length, or the
// blade length of a single leaf).
float foliage_card_aspect(const ShootDesign& design);

// The card: a quad, base at the origin, axis +Y to y = 1, x in [−w/2, w/2] with
// w = foliage_card_aspect, normal +Z, counter-clockwise seen from +Z, uv (0, 0) top left.
Mesh make_foliage_card(const ShootDesign& design);

// RGBA8 `size` × `size`, top row = the shoot's tip. Near-white blades with darker veins and a
// brown-grey twig (the leaf material's colour and the per-element colour multiply it), each
// leaf a little lighter or darker than its neighbours; alpha = coverage, antialiased.
Image8 make_foliage_texture(const ShootDesign& design, uint32_t size = 256);

// Where leaf k of the shoot sits, in card units: attachment point on the twig, blade
// direction (unit) and blade length. Exposed for tests.
struct ShootLeaf {
  glm::vec2 base{0.0f}, direction{0.0f, 1.0f};
  float length = 0.0f;
};
std::vector<ShootLeaf> shoot_leaves(const ShootDesign& design);

}  // namespace forest
