// The directions of a DDGI update's probe rays (Majercik et al. 2019, §4): ray r of pass.rays is the
// r-th spherical Fibonacci point under this update's random rotation (pass.rotation, rows). Included
// after the block Pass { DdgiParams pass; } by the passes that trace or read the rays.
#include "shared/octahedral.glsl"

vec3 probeRayDirection(int r) {
  vec3 f = sphericalFibonacci(float(r), float(pass.rays));
  return normalize(vec3(dot(pass.rotation[0].xyz, f), dot(pass.rotation[1].xyz, f), dot(pass.rotation[2].xyz, f)));
}
