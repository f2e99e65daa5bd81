// Shadow maps store distances, not depths: the distance to a point/spot light
// (cube faces), or along a directional light from its bounding plane.
in vec3 vPosition;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform int uDirectional;
layout(location = 0) out float outDistance;
void main() {
  outDistance = uDirectional != 0 ? dot(vPosition - uLightPosition, uLightDirection)
                                  : length(vPosition - uLightPosition);
}
