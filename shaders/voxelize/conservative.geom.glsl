// Three-axis conservative voxelization, triangle setup (Basgier 2015 §3.2–3.3,
// after Crassin & Green 2012 and Hasselgren et al. 2005): project each triangle
// along its dominant axis (largest projected area, so at most ~3 cells deep per
// pixel) and push its edges out by a pixel's semi-diagonal so every pixel it
// touches gets a fragment.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 vGrid[];
uniform uvec4 uResolution;
uniform float uViewport;  // the square viewport's side, ≥ every grid side
flat out int gAxis;       // dominant axis: 0 = x, 1 = y, 2 = z
flat out vec3 gA;
flat out vec3 gB;
flat out vec3 gC;
#ifdef CONSERVATIVE_VALUES
in vec3 vWorld[];
in vec2 vUv[];
flat out vec3 gWorldNormal;  // the triangle's unit normal in world space
flat out vec2 gUvCentroid;
flat out vec3 gWorld0;  // the corners in world space (gA, gB, gC's), and their uvs
flat out vec3 gWorld1;
flat out vec3 gWorld2;
flat out vec2 gUv0;
flat out vec2 gUv1;
flat out vec2 gUv2;
#endif

// Grid coordinates → (u, v, w) with w along `axis`.
vec3 swizzle(vec3 p, int axis) {
  if (axis == 0) return vec3(p.y, p.z, p.x);
  if (axis == 1) return vec3(p.z, p.x, p.y);
  return p;
}

void main() {
  vec3 n = cross(vGrid[1] - vGrid[0], vGrid[2] - vGrid[0]);
  vec3 an = abs(n);
  int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  vec2 p0 = swizzle(vGrid[0], axis).xy, p1 = swizzle(vGrid[1], axis).xy, p2 = swizzle(vGrid[2], axis).xy;
  if ((p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x) < 0.0f) {  // make it counter-clockwise
    vec2 t = p1;
    p1 = p2;
    p2 = t;
  }
  // Edge lines (interior positive), each moved out by the semi-diagonal.
  vec3 e0 = cross(vec3(p0, 1.0f), vec3(p1, 1.0f));
  vec3 e1 = cross(vec3(p1, 1.0f), vec3(p2, 1.0f));
  vec3 e2 = cross(vec3(p2, 1.0f), vec3(p0, 1.0f));
  e0.z += 0.5f * (abs(e0.x) + abs(e0.y));
  e1.z += 0.5f * (abs(e1.x) + abs(e1.y));
  e2.z += 0.5f * (abs(e2.x) + abs(e2.y));
  vec3 q[3];
  q[0] = cross(e2, e0);
  q[1] = cross(e0, e1);
  q[2] = cross(e1, e2);
  for (int i = 0; i < 3; ++i) {
    vec2 s = q[i].xy / q[i].z;  // grid cells along (u, v) = pixels
    gAxis = axis;
    gA = vGrid[0];
    gB = vGrid[1];
    gC = vGrid[2];
#ifdef CONSERVATIVE_VALUES
    vec3 wn = cross(vWorld[1] - vWorld[0], vWorld[2] - vWorld[0]);
    gWorldNormal = dot(wn, wn) > 0.0f ? normalize(wn) : vec3(0.0f);
    gUvCentroid = (vUv[0] + vUv[1] + vUv[2]) / 3.0f;
    gWorld0 = vWorld[0];
    gWorld1 = vWorld[1];
    gWorld2 = vWorld[2];
    gUv0 = vUv[0];
    gUv1 = vUv[1];
    gUv2 = vUv[2];
    gl_PrimitiveID = gl_PrimitiveIDIn;
#endif
    gl_Position = vec4(s / uViewport * 2.0f - 1.0f, 0.0f, 1.0f);
    EmitVertex();
  }
  EndPrimitive();
}
