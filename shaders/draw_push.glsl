// The vertex shaders' push constants (gpu_types.h DrawPush): the first command of the draw
// and the camera (the scene camera, or a cascade of the sun's shadow map). Needs common.glsl.
layout(push_constant) uniform DrawPushBlock { layout(offset = DRAW_PUSH_OFFSET) DrawPush draw; };

mat4 draw_view_proj() { return draw.cascade == SHADOW_NONE ? frame.view_proj : frame.shadow_view_proj[draw.cascade]; }
