// Procedural bark textures per species, generated on the CPU: one periodic height field per
// pattern (furrows, plates, lenticels...) gives both the albedo and the tangent-space normal
// map, so dark furrows are also the recessed ones. Both tile seamlessly in u and v (every
// noise is periodic on the tile: torus lattices, Worley cells with wrapped distances). The
// mesher maps u around the branch and v along it in units of bark_tile_meters, so the
// texture's features have their physical size on every branch. Deterministic: the same
// pattern, colour and size give the same bytes.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

enum class BarkPattern {
  furrowed,  // oak: deep fissures along the branch between long, broken ridges
  smooth,    // beech: smooth silver-grey with faint mottling
  birch,     // white, dark lenticels across the branch, dark fissured patches
  scaly,     // pine: orange-brown plates flaking in layers, dark fissures between
  plated,    // spruce: small rounded grey-brown plates, overlapping like scales
  generic,   // fine fibres along the branch and a few shallow furrows
};

// "furrowed", "smooth", "birch", "scaly", "plated", "generic".
std::optional<BarkPattern> parse_bark_pattern(std::string_view name);
const char* bark_pattern_name(BarkPattern pattern);

// The physical size of one texture tile (metres, square): the mesher divides bark arc
// lengths by it.
float bark_tile_meters(BarkPattern pattern);

struct BarkTextures {
  // RGBA8 sRGB-encoded colour (alpha 255): the pattern's tones times bark_color, so it is
  // the bark's whole base colour (a material using it keeps a white colour factor).
  Image8 albedo;
  // RGBA8 tangent-space normals, RGB = n * 0.5 + 0.5 (alpha 255), glTF's convention: +X
  // toward +u (right in the image), +Y toward the image's top row (−v), +Z out of the bark.
  Image8 normal;
};

// Both images `size` × `size` (top row = v 0), seamless when repeated in u and v. bark_color
// is the linear RGB the pattern's tones multiply (about its mean colour; bright ridges may
// exceed it, results clamp to 1).
BarkTextures make_bark_textures(BarkPattern pattern, glm::vec3 bark_color, uint32_t size = 256);

}  // namespace forest
