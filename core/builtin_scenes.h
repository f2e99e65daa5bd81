#pragma once
#include <string>
#include <vector>

#include "core/scene.h"

namespace vgi {
// Names accepted after "builtin:".
std::vector<std::string> builtinSceneNames();
// Appends the builtin's meshes and materials; lights and camera go to the
// out-parameters so a scene JSON can keep or replace them.
void appendBuiltin(const std::string& name, Scene& scene, std::vector<Light>& lights, Camera& camera);
}  // namespace vgi
