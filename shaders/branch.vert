#version 460
#extension GL_GOOGLE_include_directive : require
// Bark: one indirect draw per visible (or shadow-casting) tree; gl_DrawID finds the tree instance.
#extension GL_ARB_shader_draw_parameters : require
#include "common.glsl"
#include "draw_push.glsl"

layout(set = 0, binding = BINDING_COMMANDS, std430) readonly buffer Commands { DrawCommand commands[]; };

layout(location = ATTR_POSITION) in vec3 in_position;
layout(location = ATTR_NORMAL) in vec3 in_normal;
layout(location = ATTR_UV) in vec2 in_uv;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_albedo;
layout(location = 3) out vec2 out_ao_translucency;
layout(location = 4) out vec3 out_uv_layer;
layout(location = 5) out float out_sun_visibility;
layout(location = 6) flat out vec2 out_fade_shadow;  // the impostor fade; y unused (bark reads the shadow map per fragment)

void main() {
  DrawCommand d = commands[draw.command_base + gl_DrawIDARB];
  Instance inst = instances[d.instance];
  const uint model = inst.model;  // fields read where used (leaf_body.glsl says why)
  vec3 world = rotate_yaw(in_position, inst.yaw_cos_sin) * inst.position_scale.w + inst.position_scale.xyz;
  out_world = world;
  out_normal = rotate_yaw(in_normal, inst.yaw_cos_sin);
  // The bark texture (tree.frag) times the material colour: white when the texture holds
  // the colour, the model's bark_color on the neutral layer. The tint's alpha varies the
  // brightness per instance.
  out_albedo = models[model].bark_color.rgb * unpack_tint(inst.tint).a;
  out_ao_translucency = vec2(0.8, 0.0);
  out_sun_visibility = 1.0;
  out_fade_shadow = vec2(d.fade, 1.0);
  out_uv_layer = vec3(in_uv, float(models[model].bark_texture_layer));
  if ((frame.view_flags & VIEW_LAMBDA) != 0) out_albedo = lambda_color(d.shown_lambda) * 0.6;
  gl_Position = draw_view_proj() * vec4(world, 1.0);
}
