// The voxel tracers' ids, for C++ (traverse/ray_tracers.cpp's registry) and
// GLSL (shaders/traverse/tracer.glsl selects the one VGI_TRACER names; any
// other value is a compile error there, not a silent fallback).
#ifdef __cplusplus
#pragma once
#endif
#define VGI_TRACER_HIERARCHICAL 0
#define VGI_TRACER_DDA 1
#define VGI_TRACER_MARCH 2
#define VGI_TRACER_BVH 3
