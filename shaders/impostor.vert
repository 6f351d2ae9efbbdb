#version 460
#extension GL_GOOGLE_include_directive : require
// One quad per listed tree (impostor_pass.h): the shared quad pattern's 6 indices (corners 0 1
// 2, 0 2 3) per instance of the indirect draw, the instance indexing the draw's impostor list. The quad is the bounding sphere's square
// facing the viewer (the camera, or the sun for a cascade); the fragment shader finds the
// tree on it. The three views blended and their weights are per tree, chosen here from the
// direction toward the viewer in model space (impostor_math.h).
#include "common.glsl"
#include "draw_push.glsl"
#include "impostor_math.h"

layout(set = 0, binding = BINDING_IMPOSTOR_LIST, std430) readonly buffer Impostors { ImpostorEntry impostors[]; };

layout(location = 0) out vec3 out_world;  // the quad's point
layout(location = 1) flat out uint out_instance;
layout(location = 2) flat out float out_fade;
layout(location = 3) flat out uvec3 out_views;  // view i + IMPOSTOR_GRID · j
layout(location = 4) flat out vec3 out_weights;

// A quad larger than the sphere's square by this factor: a perspective camera sees the
// sphere a little wider than its radius (by 1 / cos of its half angle).
const float kQuadMargin = 1.05;

void main() {
  uint list = draw.cascade == SHADOW_NONE ? 0u : 1u + draw.cascade;
  ImpostorEntry e = impostors[list * frame.instance_count + uint(gl_InstanceIndex)];
  Instance inst = instances[e.instance];
  const vec4 sphere = models[inst.model].bounding_sphere;  // not the whole Model (leaf_body.glsl)
  float s = inst.position_scale.w;
  vec3 center = inst.position_scale.xyz + rotate_yaw(sphere.xyz, inst.yaw_cos_sin) * s;
  float radius = sphere.w * s;
  vec3 to_viewer = draw.cascade == SHADOW_NONE ? normalize(frame.camera_pos.xyz - center) : frame.sun_dir.xyz;

  vec3 v_model = rotate_yaw(to_viewer, vec2(inst.yaw_cos_sin.x, -inst.yaw_cos_sin.y));
  vec2 g = impostor_grid_position(v_model);
  vec2 cell = min(floor(g), vec2(float(IMPOSTOR_GRID - 2)));
  vec2 f = g - cell;
  uint c = uint(cell.x) + IMPOSTOR_GRID * uint(cell.y);
  if (f.x + f.y < 1.0) {  // the triangle (0,0) (1,0) (0,1) of the cell
    out_views = uvec3(c, c + 1u, c + IMPOSTOR_GRID);
    out_weights = vec3(1.0 - f.x - f.y, f.x, f.y);
  } else {  // (1,1) (1,0) (0,1)
    out_views = uvec3(c + 1u + IMPOSTOR_GRID, c + 1u, c + IMPOSTOR_GRID);
    out_weights = vec3(f.x + f.y - 1.0, 1.0 - f.y, 1.0 - f.x);
  }

  const vec2 corners[4] = vec2[4](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 corner = corners[uint(gl_VertexIndex) & 3u];
  vec3 right = impostor_right(to_viewer), up = impostor_up(to_viewer);
  out_world = center + (right * corner.x + up * corner.y) * (radius * kQuadMargin);
  out_instance = e.instance;
  out_fade = e.fade;
  gl_Position = draw_view_proj() * vec4(out_world, 1.0);
}
