// A 1.8 m human silhouette to stand beside trees in the gallery, so that every picture shows
// the tree's size at a glance (as botanical plates draw a person to scale). Built as a tiny
// tree graph (legs, torso, arms, head as tubes) meshed by the shared mesher.
#pragma once
#include "generators/model/tree_model.h"

namespace forest {

// A standing person `height` metres tall, feet on y = 0 around the origin, facing +Z: bark
// mesh only (no leaves), dark grey.
TreeModel human_figure(float height = 1.8f);

}  // namespace forest
