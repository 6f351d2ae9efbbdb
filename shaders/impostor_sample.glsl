// The tree on an impostor's quad (impostor.frag, impostor_shadow.frag): for each of the three
// views impostor.vert chose, the ray through the pixel is followed to the view's stored height
// (one parallax step: the height where the ray meets the view's plane through the centre,
// then the point of the ray at that height), and coverage, albedo, normal and that point are
// blended with the views' weights. Model space throughout. Needs common.glsl.
#include "impostor_math.h"

layout(set = 0, binding = BINDING_IMPOSTOR_ALBEDO) uniform sampler2DArray impostor_albedo;
layout(set = 0, binding = BINDING_IMPOSTOR_NORMALS) uniform sampler2DArray impostor_normals;

struct ImpostorHit {
  float alpha;    // blended coverage
  vec3 albedo;    // linear
  vec3 normal;    // model space, unit
  vec3 point;     // model space, relative to the sphere's centre
};

// View `view`'s image position of model-space point `rel` (relative to the centre): [0, 1]²,
// top row first, the sphere's square filling it.
vec2 impostor_view_uv(vec3 rel, vec3 right, vec3 up, float radius) {
  return vec2(dot(rel, right), -dot(rel, up)) / (2.0 * radius) + 0.5;
}

vec3 impostor_atlas_uv(uint view, vec2 uv, float layer) {
  const float half_texel = 0.5 / float(IMPOSTOR_VIEW_SIZE);
  vec2 cell = vec2(float(view % IMPOSTOR_GRID), float(view / IMPOSTOR_GRID));
  return vec3((cell + clamp(uv, half_texel, 1.0 - half_texel)) / float(IMPOSTOR_GRID), layer);
}

// `rel`: the quad's point relative to the centre; `ray`: unit direction of the pixel's ray.
// `sphere_radius` and `impostor_layer`: the model's (Model.bounding_sphere.w, .impostor_layer).
ImpostorHit impostor_hit(float sphere_radius, uint impostor_layer, uvec3 views, vec3 weights, vec3 rel, vec3 ray) {
  float radius = max(sphere_radius, 1e-3);
  float layer = float(impostor_layer);
  ImpostorHit hit = ImpostorHit(0.0, vec3(0.0), vec3(0.0), vec3(0.0));
  for (int k = 0; k < 3; ++k) {
    uint view = views[k];
    vec3 dir = impostor_view_direction(view % IMPOSTOR_GRID, view / IMPOSTOR_GRID);
    vec3 right = impostor_right(dir), up = impostor_up(dir);
    // The ray meets this view's plane through the centre at p0; its gradients (smooth over
    // the quad) choose the mip level of every sample of this view.
    float along = min(dot(ray, dir), -0.05);  // the views face the viewer: the ray goes away from them
    vec3 p0 = rel - ray * (dot(rel, dir) / along);
    vec2 uv0 = impostor_view_uv(p0, right, up, radius);
    vec2 dx = dFdx(uv0) / float(IMPOSTOR_GRID), dy = dFdy(uv0) / float(IMPOSTOR_GRID);
    float height = (textureGrad(impostor_normals, impostor_atlas_uv(view, uv0, layer), dx, dy).b - 0.5) * 2.0 * radius;
    vec3 p = p0 + ray * (height / along);
    vec3 at = impostor_atlas_uv(view, impostor_view_uv(p, right, up, radius), layer);
    vec4 albedo = textureGrad(impostor_albedo, at, dx, dy);
    vec4 nd = textureGrad(impostor_normals, at, dx, dy);
    float w = weights[k] * albedo.a;
    hit.alpha += w;
    hit.albedo += w * albedo.rgb;
    hit.normal += w * oct_decode_normal(nd.rg);
    hit.point += w * p;
  }
  if (hit.alpha > 0.0) {
    hit.albedo /= hit.alpha;
    hit.point /= hit.alpha;
  }
  hit.normal = length(hit.normal) > 1e-6 ? normalize(hit.normal) : vec3(0.0, 1.0, 0.0);
  return hit;
}
