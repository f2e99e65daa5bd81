// Scene loading: "builtin:NAME", a scene JSON file, or a bare model file
// (OBJ/MTL, glTF 2.0 .gltf/.glb, PLY) read through assimp; textures through
// OpenImageIO. Bad input raises vgi::Error naming the file and the value;
// recoverable problems (degenerate triangles, missing textures) are counted in
// Scene::report.
//
// Scene JSON (every key is checked; unknown keys are errors):
// {
//   "meshes": [ { "path": "model.obj" | "builtin:cornell",   // relative to the JSON file
//                 "transform": {"translate":[x,y,z], "rotate":[deg,ax,ay,az], "scale": s|[x,y,z]}
//                              | {"matrix": [16 numbers, row-major]},
//                 "material": "name",          // optional: one material for the whole file
//                 "dynamic": false,
//                 "keyframes": [ {"time": t, "translate":…, "rotate":…, "scale":…} ] } ],
//   "materials": { "name": {"albedo":[r,g,b], "texture":"file", "ks":[r,g,b],   // overrides every
//                           material of that name, or defines a new one
//                           "exponent": n, "emission":[r,g,b]} },  // overrides or new
//   "lights": [ {"type":"spot", "position":[…], "direction":[…], "intensity": [r,g,b] | x,
//                "cone_deg": half-angle, "falloff": n}
//             | {"type":"point", "position":[…], "intensity":…}
//             | {"type":"directional", "direction":[…], "irradiance":…} ],
//                each optionally with "keyframes": [ {"time": t, "position":…, "direction":…} ]
//                (a path: position for point/spot, direction for spot/directional, each key over
//                the light's own; linear between keys, clamped: Scene::placeLightsAt)
//   "environment": {"color":[r,g,b]} | {"map":"latlong.exr", "scale": s},
//   "two_sided_emission": false,   // emissive meshes (area lights) emit on their winding's
//                                  // front side only, or (true) on both (core/emitters.h)
//   "camera": {"position":[…], "target":[…], "up":[…], "fov_deg": f,
//              "near": d,              // optional: a cut-away view, nothing nearer than d along
//                                      // the view axis is seen (light transport still sees it)
//              "keyframes": [ {"time": t, "position":…, "target":…, "up":…, "fov_deg": f} ] },
//                                      // optional: a camera path (each key over the camera's
//                                      // values; linear between keys, clamped at the ends)
//   "presets": { "name": { "key": "value", … } }   (a preset for one method names it:
//              "method": "reference"; --preset then selects that method)
// }
#pragma once
#include <string>

#include "core/scene.h"

namespace vgi {

Scene loadScene(const std::string& spec);
// Throws, naming `origin`, if a coordinate (geometry bounds, camera, light) or a power (lights,
// emission, environment) lies outside what every method computes finitely with — the checks a
// scene file gets, for whatever changes a loaded scene (--camera, --light).
void checkSceneRanges(const Scene& scene, const std::string& origin);

// Reads one model file through assimp and appends its meshes/materials.
// Returns the number of meshes appended.
size_t appendModelFile(const std::string& path, Scene& scene);

// Loads an image as linear RGB (8/16-bit files are treated as sRGB); `what`
// names it in errors ("texture", "image", "environment map").
Texture loadTexture(const std::string& path, const std::string& what = "texture");

// Throws unless `path` names a regular file (or a link to one) that can be
// looked at: a device (/dev/zero), FIFO or socket would hang or stream
// forever in a reader, a folder is not a file, a name component longer than
// the file system allows is an error about this path (not an exception
// from std::filesystem). `what` names the file's role in the message.
void requireRegularFile(const std::string& path, const std::string& what);

// Checks finiteness, index ranges and drops degenerate triangles (counted).
void validateMesh(Mesh& mesh, LoadReport& report);

}  // namespace vgi
