// The leaf card's alpha-masked texture (Neubert 2012 ch5: "quad with alpha-masked texture"),
// drawn procedurally from a parametric outline per species: deterministic, no files.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include "generators/model/tree_model.h"

namespace forest {

enum class LeafShape {
  ovate,       // egg-shaped, widest below the middle (beech, lime)
  elliptic,    // widest at the middle (many broadleaves)
  lanceolate,  // long and narrow, tapering to a point (willow)
  lobed,       // obovate with rounded lobes and small ear-like base lobes (pedunculate oak)
  deltoid,     // triangular with a broad, straight base and a doubly serrate margin (birch, poplar)
  palmate,     // five rounded lobes around the petiole, palmate veins (field maple)
  needles,     // one needle shoot: needles on both sides of a twig (spruce, larch, pine)
};

inline constexpr LeafShape kLeafShapes[] = {LeafShape::ovate,   LeafShape::elliptic, LeafShape::lanceolate,
                                            LeafShape::lobed,   LeafShape::deltoid,  LeafShape::palmate,
                                            LeafShape::needles};

// "ovate", "elliptic", "lanceolate", "lobed", "deltoid", "palmate", "needles".
std::optional<LeafShape> parse_leaf_shape(std::string_view name);
const char* leaf_shape_name(LeafShape shape);

// Width of the card (and of the texture's content) relative to the blade length: the card is
// a quad [−w/2, w/2] × [0, 1] and the texture covers it exactly.
float leaf_card_aspect(LeafShape shape);

// What covers point (x, y) of one leaf's card (blade length 1, base at y = 0, x across):
// 0 nothing, 1 blade or needle, 2 secondary vein, 3 midrib, petiole or twig. The outline
// has the shape's margin (teeth, lobes); veins are pinnate, or palmate for `palmate`.
// `stroke` widens needles and the needle shoot's twig (a needle shoot drawn small on a
// branchlet card would otherwise thin out below a texel).
int leaf_texel_class(LeafShape shape, float x, float y, float stroke = 1.0f);

// RGBA8, `size` × `size`, top row = tip of the blade (v = 0), bottom row = its base. RGB is
// a near-white blade with darker midrib and veins (the material's base color and the per-leaf
// color multiply it); alpha is the outline's coverage, antialiased over about one texel.
// Transparent texels carry the blade color so that filtering does not darken the edge.
// Deterministic: the same shape and size give the same bytes.
Image8 make_leaf_texture(LeafShape shape, uint32_t size = 128);

}  // namespace forest
