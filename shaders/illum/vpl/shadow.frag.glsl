// The distance to the map's centre over the atlas's far distance, kept by the depth test (LESS).
#include "vpl_shadow.glsl"
in vec3 vWorld;
flat in vec3 vCentre;
void main() { gl_FragDepth = clamp(distance(vWorld, vCentre) / vplShadow.far, 0.0f, 1.0f); }
