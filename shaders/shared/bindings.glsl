// Every SSBO, texture and image unit the GL code binds, in one table read by
// C++ (glBind*) and GLSL (layout(binding = …)). Units may repeat only between
// resources no pass binds together: ShaderLibrary::checkBindings checks every
// program the library links, from GL's own introspection, that no two resources
// one program uses share a unit, and that each unit is within this GL's limits.
#ifdef __cplusplus
#pragma once
#endif

// ---- shader storage buffers
#define BINDING_MATERIALS 0        // SSBO PackedMaterial[] (shared/gpu_scene.glsl)
#define BINDING_TRI_MATERIAL 1     // SSBO int[] material index per triangle
#define BINDING_LIGHTS 2           // SSBO PackedLight[]
#define BINDING_ATLAS_CORNERS 3    // SSBO a mesh's VBO, read by the atlas voxelizer's passes
#define BINDING_LIGHT_FACES 4      // SSBO LightFace[] (shared/light_maps.glsl)
#define BINDING_LIGHT_RANGES 5     // SSBO ivec4[] per light: x first face, y face count
#define BINDING_PYRAMID 6          // SSBO the OR-mip pyramid's words (traverse/tracer.glsl)
#define BINDING_GRID_WORDS 7       // SSBO a binary grid's words being written (voxelizers, or_mip build)
#define BINDING_VOXEL_COUNTER 8    // SSBO uint counter of inserted points
#define BINDING_VALUE_COUNTS 9     // SSBO multi-valued grid: points per voxel
#define BINDING_VALUE_NORMAL 10    // SSBO multi-valued grid: normal sums
#define BINDING_VALUE_ALBEDO 11    // SSBO multi-valued grid: albedo sums
#define BINDING_VALUE_GLOSSY 12    // SSBO multi-valued grid: glossy sums
#define BINDING_TRACE_RAYS 13      // SSBO rays of a batch trace (traverse/trace_rays.comp)
#define BINDING_INJECT_CELL_MAX 13  // SSBO uint[]: vct's injection, per cell its pairs' largest radiance (float bits; inject_sums.glsl)
#define BINDING_TRACE_HITS 14      // SSBO their hits
#define BINDING_VALUE_RADIANCE 15  // SSBO multi-valued grid: radiance sums
#define BINDING_VALUE_RADIANCE_MAX 16  // SSBO uint: the radiance pass's maximum (float bits)
#define BINDING_VPL_FLUX 17        // SSBO float[]: the RSM flux tree (shared/vpl.glsl)
#define BINDING_DDGI_PROBES 17     // SSBO vec4[]: ddgi's probe offsets (xyz) and states (w) (illum/ddgi/probes.glsl; vpl's flux tree elsewhere)
#define BINDING_VPLS 18            // SSBO Vpl[] (shared/vpl.glsl): bounce-major, chain-minor
#define BINDING_AVG 19             // SSBO uint[]: the approximate visibility grid's cells (shared/avg.glsl)
#define BINDING_BVH_NODES 20       // SSBO vec4[]: the BVH's nodes (shared/trace_bvh.glsl, traverse/gpu_bvh.h)
#define BINDING_BVH_TRIS 21        // SSBO vec4[]: its triangles, in leaf order
#define BINDING_BVH_NORMALS 22     // SSBO vec4[]: per triangle (scene order) its normals (traverse/gpu_bvh.h)
#define BINDING_EMITTERS 23        // SSBO PackedEmitter[] (shared/emitters.glsl; illum/resources/gpu_emitters.h)
#define BINDING_EMITTER_OF 24      // SSBO int[]: per triangle (scene order) its emitter, or -1
#define BINDING_SCENE_VERTICES 25  // SSBO float[]: the GPU scene's vertex buffer (core/gpu_scene.h, per corner)
#define BINDING_SVO_NODES 26       // SSBO uint[]: the sparse octree's nodes (shared/sparse_octree.glsl, voxelize/sparse_octree.h)
#define BINDING_SVO_COORDS 27      // SSBO uint[]: per node its packed cell (svoPackCell)
#define BINDING_SVO_FRAGMENTS 28   // SSBO uint[]: the octree's fragments (packed cells)
#define BINDING_GATHER_FIXUP 29    // SSBO the gather kit's fix-up list (illum/gather/gather.glsl: GatherFixup)
#define BINDING_VALUE_DIRECTION 30  // SSBO vct's directional injection: per cell the leaving direction's sums (illum/vct/inject_sums.glsl)
#define BINDING_ATLAS_POINTS 31     // SSBO a kept atlas's valid texels (x | y << 16), its insertions' invocations

// ---- uniform buffers (std140 blocks of params structs: illum/framework/compute_pass.h)
#define UBO_PASS 0         // a compute pass's own parameters: `uniform Pass { T p; }`
#define UBO_VOXEL_HITS 1   // the voxel-hit rules of illum/voxel_hits.glsl (VoxelHitParams)
#define UBO_GATHER 2       // the gather kit's parameters (illum/gather/params.glsl: GatherParams)
#define UBO_VPL_SHADOW 3   // the VPL shadow-map atlas (illum/vpl/params.glsl: VplShadowParams)

// ---- textures (samplers)
#define TEXUNIT_GBUFFER_POSITION 0          // world position, w = 1 where a surface was seen
#define TEXUNIT_GBUFFER_NORMAL 1            // shading normal towards the viewer, w = material
#define TEXUNIT_GBUFFER_ALBEDO 2
#define TEXUNIT_PASS_INPUT 3                // a pass's own input texture
#define TEXUNIT_GBUFFER_GEOMETRIC_NORMAL 4  // the triangle's normal (the shadow test's receiver plane)
#define TEXUNIT_ATLAS_POSITION 5            // atlas voxelizer: the rendered atlas' positions
#define TEXUNIT_ATLAS_TRIANGLE 6            // … its triangle ids
#define TEXUNIT_ATLAS_NORMAL 7              // … normals (multi-valued grids)
#define TEXUNIT_ALBEDO_ARRAY 8              // sampler2DArray of albedo textures (one size)
#define TEXUNIT_ENV_MAP 9                   // sampler2D lat-long environment
#define TEXUNIT_LIGHT_DISTANCE 10           // sampler2DArray R32F
#define TEXUNIT_LIGHT_POSITION 11           // sampler2DArray RGBA32F (w = 1 where a surface was seen)
#define TEXUNIT_LIGHT_NORMAL 12             // sampler2DArray RGBA16F
#define TEXUNIT_LIGHT_RADIANCE 13           // sampler2DArray RGBA16F, reflected direct radiance (diffuse)
#define TEXUNIT_ATLAS_ALBEDO 14             // atlas voxelizer: albedo (multi-valued grids)
#define TEXUNIT_ATLAS_GLOSSY 15             // … glossy
#define TEXUNIT_VALUE_OCCUPANCY 16          // sampler3D R8: 1 where a cell has atlas points (voxelize/value_textures.h)
#define TEXUNIT_VALUE_NORMAL 17             // sampler3D RGBA16F mean normal (xyz)
#define TEXUNIT_VALUE_ALBEDO 18             // sampler3D RGBA8 mean albedo (rgb)
#define TEXUNIT_VALUE_GLOSSY 19             // sampler3D RGBA16F mean ks (rgb), exponent code (w)
#define TEXUNIT_VALUE_COUNT 20              // usampler3D R32UI atlas points per cell
#define TEXUNIT_VALUE_ANISO 21              // 21…26: the six faces of one channel's anisotropic chain
#define TEXUNIT_PASS_INPUT2 27              // a pass's second input texture
#define TEXUNIT_VALUE_RADIANCE 28           // sampler3D RGBA16F mean diffuse direct radiance (rgb)
#define TEXUNIT_ATLAS_RADIANCE 29           // atlas voxelizer: radiance (multi-valued grids)
#define TEXUNIT_VPL_SHADOW 30               // sampler2D: the VPL shadow-map atlas (avg; illum/vpl/vpl_shadow.glsl)
#define TEXUNIT_GATHER_FIXUP 31             // sampler2D RGBA32F: the gather kit's full-rate fix-ups (w = 1 where made)
#define TEXUNIT_VALUE_DIRECTION 32          // sampler3D RGBA8_SNORM: vct's level-0 direction of the leaving light (illum/resources/cone_volume.h)

// ---- images
#define IMAGE_OUTPUT 0                 // a pass's output
#define IMAGE_SAMPLE 0                 // the sample loop's "image" channel a method writes
#define IMAGE_SAMPLE_AOV0 1            // the first output channel (e.g. indirect)
#define IMAGE_SAMPLE_AOV1 2            // the second (e.g. direct)
#define IMAGE_SAMPLE_AOV2 3            // a third (vct: ao)
#define IMAGE_SAMPLE_AOV3 4            // a fourth (vct: specular)
#define IMAGE_OUTPUT2 1                // a pass's second output (vct's diffuse pass: the AO)
#define IMAGE_ACCUMULATE_SAMPLE 0      // shaders/illum/accumulate.comp
#define IMAGE_ACCUMULATE_SUM 1
#define IMAGE_ACCUMULATE_COMPENSATION 2
#define IMAGE_TEMPORAL_SUM 0           // shaders/illum/temporal/resolve.comp: the film's sum
#define IMAGE_TEMPORAL_HISTORY 1       // the filtered image of the previous frame
#define IMAGE_TEMPORAL_OUTPUT 2        // this frame's
#define IMAGE_VALUE_OCCUPANCY 1        // voxelize/value_resolve.comp: the textures it writes
#define IMAGE_VALUE_NORMAL 2
#define IMAGE_VALUE_ALBEDO 3
#define IMAGE_VALUE_GLOSSY 4
#define IMAGE_VALUE_COUNT 5
#define IMAGE_VALUE_RADIANCE 6
#define IMAGE_VALUE_DIRECTION 7        // illum/vct/direction_resolve.comp: vct's level-0 direction
