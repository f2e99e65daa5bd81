// Atlas rendering (VGI §3.1): a mesh drawn in its texture-atlas space, writing
// the position (and, for multi-valued grids, normal and material) of every
// covered texel. Positions are offsets from the voxel grid's origin (uModel is
// object → world − origin, composed in double on the CPU): interpolated in world
// coordinates they would snap to the float steps of the world far from its
// origin (1 unit at 10^7) instead of the steps of the grid's box.
layout(location = 0) in vec3 inPosition;  // object space
layout(location = 1) in vec2 inAtlasUv;   // [0, 1]²
layout(location = 2) in float inTriangle;
layout(location = 3) in vec3 inNormal;    // object space
layout(location = 4) in vec2 inTexUv;     // the mesh's texture coordinates
uniform mat4 uModel;  // object → offset from the grid's origin at the frame's time
out vec3 vPosition;
out vec3 vNormal;
out vec2 vTexUv;
flat out int vTriangle;
void main() {
  vPosition = (uModel * vec4(inPosition, 1.0f)).xyz;
  vNormal = transpose(inverse(mat3(uModel))) * inNormal;
  vTexUv = inTexUv;
  vTriangle = int(inTriangle);
  gl_Position = vec4(inAtlasUv * 2.0f - 1.0f, 0.0f, 1.0f);
}
