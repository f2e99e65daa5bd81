// Path vertices through the voxel grid, shared by the GL modules that trace
// rays from surface points and shade where they stop (voxelpath's paths, vpl's
// bounce VPLs): the first hit with the own-band pass rule (trace) and the hit
// vertex from the multi-valued grids (hitVertex). Include after
// traverse/tracer.glsl, shared/light_maps.glsl and shared/value_textures.glsl.
#include "voxel_hit_params.glsl"
layout(std140, binding = UBO_VOXEL_HITS) uniform VoxelHits { VoxelHitParams hits; };

// A path vertex as the grid knows it.
struct Vertex {
  vec3 p, n;
  BrdfParams brdf;
};

// The first voxel hit along (o, d), and its RSM back-projection. With
// hits.passThrough the ray goes on past a hit (up to kMaxPasses times) within a
// voxel diagonal of the start's tangent plane — the start is only half a
// diagonal off its surface, so it may be the start's own voxel — when the
// cell's mean normal is the start's up to sign (the grid keeps the mesh's
// normals, which need not face the viewer) or the hit gives no light.
// Measured against reference path (docs/BENCHMARKS.md): the normal rule
// alone loses 2.5 % of the indirect light (in corners); adding nearfield's
// pass of voxels a light sees through loses 7 % on the Cornell box (a path
// that passes them goes on past real, unlit surfaces); this rule: 1.1 % (room) to 1.5 % (Cornell box).
bool trace(vec3 o, vec3 d, vec3 n, out float t, out uvec3 voxel, out BackProjection b) {
  ResumableRay ray = resumableRay(o, d, hits.traceLength);
  while (nextHit(ray)) {
    t = hitDistance(ray);
    voxel = ray.hit.voxel;
    precise float height = dot(d, n) * t + hits.offset;
    bool band = hits.passThrough != 0 && height < hits.voxelDiagonal;
    // The normal rule needs no back-projection: a band hit it passes costs one fetch.
    vec4 nv = band ? texelFetch(valueNormal, ivec3(voxel), 0) : vec4(0.0f);
    if (band && abs(dot(nv.xyz, n)) > 0.8f * length(nv.xyz) && passHit(ray, hits.voxelDiagonal)) continue;
    b = rsmBackProject(o, d, t, hits.voxelDiagonal, hits.traceLength, hits.backProjection == BACK_PROJECTION_PLANE);
    if (band && b.radiance == vec3(0.0f) && passHit(ray, hits.voxelDiagonal)) continue;
    return true;
  }
  return false;
}

// The hit vertex in voxel `voxel`, entered at distance t along (o, d).
// Returns false where the grid holds no values there (a cell the binary grid
// set but no atlas point reached): the path ends.
bool hitVertex(vec3 o, vec3 d, float t, uvec3 voxel, out Vertex v) {
  ivec3 c = ivec3(voxel);
  float occ = texelFetch(valueOccupancy, c, 0).x;
  if (occ <= 0.0f) return false;
  vec3 mean = texelFetch(valueNormal, c, 0).xyz / occ;
  float len = length(mean);
  // Two sides of a wall in one cell cancel: the side the ray meets is the one facing it.
  vec3 n = len > 1e-3f ? mean / len : -d;
  if (dot(n, d) > 0.0f) n = -n;
  v.n = n;
  v.brdf.albedo = texelFetch(valueAlbedo, c, 0).xyz / occ;
  vec4 g = texelFetch(valueGlossy, c, 0) / occ;
  v.brdf.ks = hits.glossy != 0 ? vec3(g.x, g.y, g.z) : vec3(0.0f);
  v.brdf.exponent = decodeExponent(g.w);
  precise vec3 entry = o + t * d;
  v.p = entry;
  if (hits.hitPoint != VOXEL_HIT_ENTRY) {
    GridParams grid = gridFromUniforms();
    vec3 centre = gridToWorld(grid, vec3(voxel) + vec3(0.5f));
    v.p = centre;
    if (hits.hitPoint == VOXEL_HIT_PLANE) {
      // The plane through the centre with the mean normal, met within the voxel.
      float cd = dot(d, n);
      if (cd < -1e-3f) {
        float ts = clamp(dot(centre - o, n) / cd, t, t + hits.voxelDiagonal);
        v.p = o + ts * d;
      } else {
        v.p = entry;
      }
    }
  }
  return true;
}

