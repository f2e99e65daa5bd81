// The distance to the map's centre over uShadowFar, kept by the depth test (LESS).
uniform float uShadowFar;
in vec3 vWorld;
flat in vec3 vCentre;
void main() { gl_FragDepth = clamp(distance(vWorld, vCentre) / uShadowFar, 0.0f, 1.0f); }
