#version 460
// forest walk's copy pass (when the window's format cannot be blitted to): full-screen triangle.
void main() {
  vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
}
