// The VPL shadow-map atlas (vpl_shadow.glsl), instanced: instance
// slot · faces + face draws the scene into that face's square of the atlas,
// clipped to it (and, for a paraboloid, to the VPL's hemisphere). Empty slots
// draw nothing.
#include "vpl_shadow.glsl"
layout(location = 0) in vec3 inPosition;
layout(std430, binding = BINDING_VPLS) readonly buffer Vpls { Vpl vpls[]; };
out vec3 vWorld;
flat out vec3 vCentre;
out float gl_ClipDistance[6];
void main() {
  int faces = vplShadowFaces();
  uint s = uint(gl_InstanceID / faces);
  int f = gl_InstanceID % faces;
  Vpl v = vpls[s];
  vWorld = inPosition;
  vCentre = vplShadowCentre(v);
  vec4 c = vplShadowClip(v, f, inPosition - vCentre);
  // The face's clip space → its square of the atlas (affine in x/w, y/w, so in clip space).
  vec2 o = vec2(vplShadowFaceOrigin(s, f));
  vec2 scale = float(vplShadow.res) / vec2(vplShadow.atlasWidth, vplShadow.atlasHeight), shift = (2.0f * o + float(vplShadow.res)) / vec2(vplShadow.atlasWidth, vplShadow.atlasHeight) - 1.0f;
  gl_Position = vec4(c.xy * scale + c.w * shift, 0.0f, c.w);
  gl_ClipDistance[0] = c.w + c.x;
  gl_ClipDistance[1] = c.w - c.x;
  gl_ClipDistance[2] = c.w + c.y;
  gl_ClipDistance[3] = c.w - c.y;
  gl_ClipDistance[4] = vplShadowCubeFaces() ? c.w - 1e-4f * vplShadow.far : c.z + 1e-3f;
  // A hemicube keeps what lies over the VPL's plane (through the VPL, not the lifted centre): a
  // receiver the VPL lights lies there, and so does whatever hides it from the centre.
  gl_ClipDistance[5] = vplShadow.kind == VPL_MAP_HEMICUBE ? dot(inPosition - v.position.xyz, v.normal.xyz) : 1.0f;
  if (v.position.w == 0.0f) gl_ClipDistance[4] = -1.0f;
}
