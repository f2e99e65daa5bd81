#include "illum/framework/resources.h"

#include <algorithm>

#include "core/emitters.h"
#include "core/profiler.h"
#include "core/scene.h"

namespace vgi {

void requireGl(const ResourceNeed& need, const std::string& method, bool gl) {
  if (!gl) fail("method '", method, "' runs on the CPU but asks for the GL resource '", need.kind(), "'");
}

SceneNeeds& SceneNeeds::add(const ResourceNeed& need) {
  if (std::find(declared_.begin(), declared_.end(), need) == declared_.end()) declared_.push_back(need);
  return *this;
}

namespace {
// Depth first: a need's dependencies before it, each key once.
void addClosure(const ResourceNeed& need, std::vector<ResourceNeed>& out, int depth) {
  VGI_CHECK(depth < 32);  // the kinds' dependencies form no cycle
  if (std::find(out.begin(), out.end(), need) != out.end()) return;
  for (auto& d : need.kindRow().dependencies(need)) addClosure(d, out, depth + 1);
  out.push_back(need);
}
}  // namespace

std::vector<ResourceNeed> SceneNeeds::closure() const {
  std::vector<ResourceNeed> out;
  for (auto& n : declared_) addClosure(n, out, 0);
  return out;
}

std::vector<std::string> SceneNeeds::names() const {
  std::vector<std::string> n;
  if (gbuffer) n.push_back("gbuffer");
  for (auto& need : closure())
    for (auto& name : need.kindRow().names(need)) n.push_back(name);
  return n;
}

bool SceneNeeds::operator==(const SceneNeeds& o) const {
  return gbuffer == o.gbuffer && closure() == o.closure();
}

void SceneNeeds::check(const std::string& method, bool gl) const {
  for (auto& need : closure()) need.kindRow().check(need, *this, method, gl);
}

SceneResources::SceneResources(const Scene& scene, SceneNeeds needs, GlContext* gl, ShaderLibrary* shaders,
                               std::vector<float> frameTimes, int threads)
    : scene_(scene),
      needs_(std::move(needs)),
      gl_(gl),
      shaders_(shaders),
      frameTimes_(std::move(frameTimes)),
      threads_(threads) {
  VGI_CHECK(bool(gl_) == bool(shaders_));
  for (auto& need : needs_.closure()) entries_.push_back({need, &need.kindRow(), nullptr});
}

SceneResources::~SceneResources() {
  // Dependents first: a resource may hold views of what it depends on.
  while (!entries_.empty()) entries_.pop_back();
}

ShaderLibrary& SceneResources::shaders() const {
  if (!shaders_) fail("internal: a CPU method's resource asked for GL shaders");
  return *shaders_;
}

bool SceneResources::dynamic() const { return scene_.hasDynamicMeshes(); }

bool SceneResources::update(float time, Profiler& prof) {
  const bool rebuild = first_ || (dynamic() && time != time_);
  time_ = time;
  for (auto& e : entries_) e.changed = e.rebuilt = false;
  if (!rebuild) {
    if (lightsChanged_) {
      placeLights();
      if (!sampleLights_) relightAll(prof);  // (else beginSample places and relights the sample's lights)
    }
    lightsChanged_ = false;
    return false;
  }
  lightsChanged_ = false;
  // The GL lights: the scene's delta lights, and with area lights a spot light per emitter point.
  const bool glLights =
      std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.kind->drawsLights; });
  emitters_ = std::make_unique<Emitters>(Emitters::ofScene(scene_, time));
  sampleLights_ = glLights && !emitters_->empty();
  placeLights();
  // A resource that fails to build is dropped, and the next update builds again from it on (the
  // viewer retries, or restores its previous scene): built once means every entry built.
  for (auto& e : entries_) {
    try {
      if (!e.resource) e.resource = e.kind->create(e.need, *this);
      e.changed = e.resource->update(*this, e.need, prof);
    } catch (...) {
      e.resource.reset();
      throw;
    }
    e.rebuilt = e.changed;
  }
  first_ = false;
  return true;
}

void SceneResources::placeLights() {
  lights_ = scene_.lights;
  if (sampleLights_) {
    // Placeholder points (sample 0, seed 0) give the light count and types;
    // beginSample places them.
    for (const Light& l : emitters_->spotLights(emitterSequence(0, 0))) lights_.push_back(l);
    lightsKey_ = -1;
  }
}

void SceneResources::relightAll(Profiler& prof) {
  for (auto& e : entries_) e.changed = e.resource && e.resource->relight(*this, e.need, prof);
}

void SceneResources::beginSample(int k, uint32_t seed, Profiler& prof) {
  if (!sampleLights_) return;
  const long long key = (static_cast<long long>(seed) << 31) | k;
  if (key == lightsKey_) return;
  lightsKey_ = key;
  lights_ = scene_.lights;
  for (const Light& l : emitters_->spotLights(emitterSequence(k, seed))) lights_.push_back(l);
  relightAll(prof);
}

void SceneResources::adopt(SceneResources& old) {
  VGI_CHECK(first_ && &old.scene_ == &scene_);
  // Nothing to take when it built nothing, or built for another context (a GL method after a CPU
  // one) or another animation (a grid box spans the frames').
  if (old.first_ || old.gl_ != gl_ || old.frameTimes_ != frameTimes_) return;
  for (auto& e : entries_)
    for (auto& o : old.entries_)
      if (o.resource && o.need.sameKey(e.need)) {
        e.resource = std::move(o.resource);
        for (auto& name : e.kind->names(e.need)) adopted_.push_back(name);
      }
}

bool SceneResources::changed(const ResourceNeed& need) const {
  for (auto& e : entries_)
    if (e.need == need) return e.changed;
  fail("internal: a resource asked whether '", need.key(), "' changed without depending on it");
}

void* SceneResources::find(const std::type_info& t, const ResourceNeed* need, bool required) const {
  void* found = nullptr;
  for (auto& e : entries_) {
    if (need && !(e.need == *need)) continue;
    void* p = e.resource ? e.resource->offer(t) : nullptr;
    if (!p) continue;
    if (found) fail("internal: two resources offer a ", t.name(), ": read it by its need");
    found = p;
  }
  if (!found && required)
    fail("internal: a method read a ", t.name(), need ? " of " + need->key() : std::string(),
         " it did not declare in its needs (or before the first update)");
  return found;
}

std::vector<std::string> SceneResources::built() const {
  std::vector<std::string> n;
  for (auto& e : entries_)
    if (e.resource)
      for (auto& name : e.kind->names(e.need)) n.push_back(name);
  return n;
}

double SceneResources::bytes() {
  nlohmann::json extra = nlohmann::json::object();
  addStats(extra);
  double sum = 0;
  for (auto& [key, s] : extra.items())
    if (s.contains("bytes") && s["bytes"].is_number()) sum += s["bytes"].get<double>();
  return sum;
}

void SceneResources::addStats(nlohmann::json& extra) {
  for (auto& e : entries_) {
    if (!e.resource || e.kind->statsKey.empty()) continue;
    nlohmann::json s = e.resource->stats();
    if (s.is_null()) continue;
    s["rebuilt_this_frame"] = e.rebuilt;
    extra[e.kind->statsKey] = std::move(s);
  }
}

}  // namespace vgi
