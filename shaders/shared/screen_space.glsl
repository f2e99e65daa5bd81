// The screen-space tests of ssdo (Ritschel, Grosch, Seidel 2009, §3; shaders/illum/ssdo/gather.comp.glsl),
// shared GLSL and C++ (tests/illum/ssdo_test.cpp checks them on the CPU).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

// Whether point X is occluded by the surface the camera sees at X's pixel — its point P and its normal
// N, which faces the camera: X lies more than eps below that surface's tangent plane (so a plane never
// occludes its own points, or any above it), and, with thickness > 0, less than `thickness` behind P
// along the view axis `forward` (0: the paper's test, a surface extends without limit behind it).
SHARED_FN bool screenOccluded(vec3 X, vec3 P, vec3 N, vec3 forward, float eps, float thickness) {
  float below = -dot(X - P, N);
  float behind = dot(X - P, forward);
  return below > eps && (thickness <= 0.0f || behind < thickness);
}

// The paper's indirect bounce (§3.2) as a share of the N directions' mean: a sender patch of area
// A_s = π r² / N at ps with normal ns seen from the receiver p with normal n gives
// A_s cos θ_s cos θ_r / (π d²) = (r² / N) cos θ_s cos θ_r / d², here times N and clamped to 1 (the
// paper clamps d): one patch stands for at most its direction's share.
SHARED_FN float ssdoPatchShare(vec3 p, vec3 n, vec3 ps, vec3 ns, float r) {
  vec3 toSender = ps - p;
  float d2 = max(dot(toSender, toSender), 1e-30f);
  float len = sqrt(d2);
  float cosR = max(dot(n, toSender) / len, 0.0f);
  float cosS = max(-dot(ns, toSender) / len, 0.0f);
  return min(r * r * cosS * cosR / d2, 1.0f);
}

SHARED_END
