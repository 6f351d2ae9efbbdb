#version 460
// A pulled leaf's triangle (leaf_pulled.vert): the point its vertex shader made, with the
// card's frame, becomes the triangle around the card (Model.card_corners) that leaf.vert's
// three vertices would make, so the fragment shaders (tree.frag, leaf_msaa.frag,
// shadow_leaf.frag) see the same inputs. The vertex shader's buffer reads are made once a leaf
// instead of once a corner (bench/results/leaf_vertex_cost.md); this stage only adds. A leaf
// shrunk to nothing (the end of the pruning transition) makes no triangle.
layout(points) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec4 in_origin_layer[];
layout(location = 1) in vec4 in_normal_sun[];
layout(location = 2) in vec4 in_albedo_fade[];
layout(location = 3) in vec4 in_axis_x_ao[];
layout(location = 4) in vec4 in_axis_y_translucency[];
layout(location = 5) in vec4 in_clip_origin[];
layout(location = 6) in vec4 in_clip_x[];
layout(location = 7) in vec4 in_clip_y[];
layout(location = 8) in vec4 in_corner[][3];
layout(location = 11) in float in_leaf_shadow[];  // the shadow map at the card's centre (leaf_body.glsl)

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_albedo;
layout(location = 3) out vec2 out_ao_translucency;
layout(location = 4) out vec3 out_uv_layer;
layout(location = 5) out float out_sun_visibility;
layout(location = 6) flat out vec2 out_fade_shadow;

void main() {
  if (in_clip_x[0] == vec4(0.0) && in_clip_y[0] == vec4(0.0)) return;
  for (uint c = 0u; c < 3u; ++c) {
    vec4 corner = in_corner[0][c];
    out_world = in_origin_layer[0].xyz + corner.x * in_axis_x_ao[0].xyz + corner.y * in_axis_y_translucency[0].xyz;
    out_normal = in_normal_sun[0].xyz;
    out_albedo = in_albedo_fade[0].rgb;
    out_ao_translucency = vec2(in_axis_x_ao[0].w, in_axis_y_translucency[0].w);
    out_uv_layer = vec3(corner.zw, in_origin_layer[0].w);
    out_sun_visibility = in_normal_sun[0].w;
    out_fade_shadow = vec2(in_albedo_fade[0].w, in_leaf_shadow[0]);
    gl_Position = in_clip_origin[0] + corner.x * in_clip_x[0] + corner.y * in_clip_y[0];
    EmitVertex();
  }
  EndPrimitive();
}
