// What a method needs of a scene, as keyed specs of resource kinds, and the
// keyed cache that builds exactly that and keeps it across the frames of an
// animation and across method or parameter changes.
//
// A resource kind (illum/resources/kinds.cpp lists them: the GPU scene, light
// maps, the binary grid, its OR-mip pyramid, value grids, the Embree BVH, the
// occluders, the cone volume, the GPU BVH, the GPU emitters) has a spec type, the kinds its spec depends on,
// checks, and a Resource that builds, updates (animation time) and relights.
// A method's needs() returns specs; two specs with the same key are one
// resource. SceneResources builds the needs and their dependencies in
// dependency order at the first update(time), and at each later update of a
// scene with dynamic meshes makes them current again (each resource decides
// what moves: the GPU scene's vertices, the dynamic meshes' voxels — the atlas
// voxelizer keeps the static meshes' grid, VGI §3.2 —, the pyramid, the light
// maps, the BVH). Area lights (core/emitters.h) come with every method: the
// CPU methods sample them from the BVH's emitters; for the GL methods
// beginSample(k) turns one emitter point per sample into spot lights, and the
// resources that depend on the lights relight. built() names what was
// actually allocated, so the stats, `vgi compare` and the registry tests read
// facts, not declarations.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/error.h"

namespace vgi {

class GlContext;
class Profiler;
struct Scene;
class ShaderLibrary;
struct Light;
class Emitters;
class SceneNeeds;
class SceneResources;
struct ResourceKind;

// One resource of a kind, by its spec. A spec type has
//   static constexpr const char* kKind;   the kind's name in the kinds table
//   static const ResourceKind& row();     its row of the kinds table (illum/resources/kinds.h): the
//                                         framework reads a need's kind from the need, not a table
//   nlohmann::json key() const;           what is allocated: a resource with this key is
//                                         adopted across method and parameter changes
// and may have
//   nlohmann::json settings() const;      what else decides its contents (the resource
//                                         updates them on an adopted one: e.g. the light
//                                         maps the value grids' radiance comes from)
// Needs with equal key and settings are one resource.
class ResourceNeed {
 public:
  template <class Spec>
  ResourceNeed(const Spec& spec)  // NOLINT: a spec is a need
      : kind_(Spec::kKind),
        key_(std::string(Spec::kKind) + spec.key().dump()),
        full_(key_ + settingsOf(spec, 0).dump()),
        spec_(std::make_shared<Spec>(spec)),
        type_(&typeid(Spec)),
        row_(&Spec::row()) {}
  const std::string& kind() const { return kind_; }
  const ResourceKind& kindRow() const { return *row_; }
  const std::string& key() const { return key_; }
  template <class Spec>
  const Spec& spec() const {
    VGI_CHECK(*type_ == typeid(Spec));
    return *static_cast<const Spec*>(spec_.get());
  }
  bool sameKey(const ResourceNeed& o) const { return key_ == o.key_; }
  bool operator==(const ResourceNeed& o) const { return full_ == o.full_; }
  bool operator!=(const ResourceNeed& o) const { return !(*this == o); }

 private:
  template <class Spec>
  static auto settingsOf(const Spec& s, int) -> decltype(s.settings()) {
    return s.settings();
  }
  template <class Spec>
  static nlohmann::json settingsOf(const Spec&, long) {
    return nullptr;
  }
  std::string kind_, key_, full_;
  std::shared_ptr<const void> spec_;
  const std::type_info* type_;
  const ResourceKind* row_;
};

// A built resource. The cache calls update() at every update that builds (the
// first, and each new time of a scene with dynamic meshes) and relight() when
// the lights change, in dependency order: its dependencies are current.
class Resource {
 public:
  virtual ~Resource() = default;
  // Makes it current for res.time() and `need` (its spec: an adopted
  // resource may be given other settings than it was built with); returns
  // whether its contents changed (dependents read that as res.changed(dependency)).
  virtual bool update(SceneResources& res, const ResourceNeed& need, Profiler& profiler) = 0;
  // The lights (res.lights()) changed: redo what depends on them; returns whether anything changed.
  virtual bool relight(SceneResources& res, const ResourceNeed& need, Profiler& profiler) { return false; }
  // For the render's stats (after the image: it may read back); null: none.
  virtual nlohmann::json stats() { return nullptr; }
  // The object of type `t` a method reads through SceneResources::get<T>, or null.
  virtual void* offer(const std::type_info& t) = 0;

 protected:
  // offer() for a resource that offers these objects (a null pointer offers nothing).
  template <class... T>
  static void* offerOf(const std::type_info& t, T*... objects) {
    void* found = nullptr;
    ((found = (!found && objects && t == typeid(T)) ? static_cast<void*>(objects) : found), ...);
    return found;
  }
};

// A row of the kinds table (illum/resources/kinds.cpp).
struct ResourceKind {
  std::string name;
  std::string description;
  // The resources this one reads (built before it, adopted with it).
  std::vector<ResourceNeed> (*dependencies)(const ResourceNeed& need);
  // Throws (naming `method`) if it cannot be built: on this device (gl or
  // not), with these other needs, or in this machine's memory.
  void (*check)(const ResourceNeed& need, const SceneNeeds& all, const std::string& method, bool gl);
  // The stats' names of what it allocates (usually {name}; light maps: "rsm" or "light_maps").
  std::vector<std::string> (*names)(const ResourceNeed& need);
  // Made at the first update, its dependencies current.
  std::unique_ptr<Resource> (*create)(const ResourceNeed& need, SceneResources& res);
  // The key of its stats in a render's `extra` (empty: none).
  std::string statsKey;
  // It draws the scene's GL lights (the GPU scene): with area lights, SceneResources then places a
  // spot light per emitter point each sample.
  bool drawsLights = false;
};

// The check of a GL-only kind: throws, naming `method`, when one that runs on the CPU asks for it.
void requireGl(const ResourceNeed& need, const std::string& method, bool gl);

// The resources one render of a method uses, and whether it draws the
// G-buffer (the sample loop's render target of the image size; it draws the
// GPU scene, which a method declares with it: needGBuffer, illum/resources/gpu_scene.h).
// GL methods get GL resources; CPU methods get host ones.
class SceneNeeds {
 public:
  bool gbuffer = false;
  // Adds a need (and, in the cache, its dependencies); a need already present is kept once.
  SceneNeeds& add(const ResourceNeed& need);
  const std::vector<ResourceNeed>& declared() const { return declared_; }
  // The first declared need of this spec type, or null.
  template <class Spec>
  const Spec* find() const {
    for (auto& n : declared_)
      if (n.kind() == Spec::kKind) return &n.spec<Spec>();
    return nullptr;
  }
  // The declared needs and their dependencies, each once, dependencies first.
  std::vector<ResourceNeed> closure() const;
  // The stats' names of all of it: "gbuffer" first, then each resource's in closure order.
  std::vector<std::string> names() const;
  // The same resources (a render job keeps its resources when they are).
  bool operator==(const SceneNeeds& o) const;
  // Throws if a need cannot be built (see ResourceKind::check), naming `method`.
  void check(const std::string& method, bool gl) const;

 private:
  std::vector<ResourceNeed> declared_;
};

class SceneResources {
 public:
  // gl/shaders: set for a GL method (then GL resources are made), null for a CPU one.
  SceneResources(const Scene& scene, SceneNeeds needs, GlContext* gl, ShaderLibrary* shaders,
                 std::vector<float> frameTimes, int threads);
  ~SceneResources();
  SceneResources(const SceneResources&) = delete;
  SceneResources& operator=(const SceneResources&) = delete;

  // Makes the resources current for animation time `time` (see above); returns
  // whether anything was (re)built.
  bool update(float time, Profiler& profiler);
  // The scene's delta lights moved (same count and types): the next update
  // relights what depends on them (the light maps, the atlas grid's radiance,
  // the cone volume's injection), keeping the rest.
  void lightsChanged() { lightsChanged_ = true; }
  // Takes over from `old` (the same scene, context and frame times; nothing
  // built here yet) every resource whose key these needs also hold (its
  // settings are updated at the first update), so that a
  // method switch or a parameter change rebuilds only what differs. What is
  // taken is listed by adopted() (the stats' names); `old` keeps the rest, to be dropped.
  void adopt(SceneResources& old);
  const std::vector<std::string>& adopted() const { return adopted_; }

  const SceneNeeds& needs() const { return needs_; }

  // Before sample k of a run seeded `seed`: with area lights and GL lights
  // (a GPU scene built), the lights become the scene's delta lights plus the
  // spot lights of emitter point emitterSequence(k, seed), and the resources
  // relight for them. No-op otherwise.
  void beginSample(int k, uint32_t seed, Profiler& profiler);
  // The lights the GL programs see now (see beginSample).
  const std::vector<Light>& lights() const { return lights_; }
  // Whether the lights follow the sample (area lights on GL resources):
  // beginSample relights, so an update need not light what it builds.
  bool sampleLights() const { return sampleLights_; }

  // The object of type T the declared resources offer (GpuScene, LightMaps,
  // GlPyramid, GridBox, …): throws if none does (a method reads only what it
  // declared, so `built` stays true) or if two do (then name the need).
  template <class T>
  T& get() const {
    return *static_cast<T*>(find(typeid(T), nullptr, true));
  }
  template <class T>
  T& get(const ResourceNeed& need) const {
    return *static_cast<T*>(find(typeid(T), &need, true));
  }
  // The same, null where no declared resource offers it (or before the first update).
  template <class T>
  T* tryGet() const {
    return static_cast<T*>(find(typeid(T), nullptr, false));
  }
  template <class T>
  T* tryGet(const ResourceNeed& need) const {
    return static_cast<T*>(find(typeid(T), &need, false));
  }
  // Whether `need` changed in the update or relight under way (its dependents read this).
  bool changed(const ResourceNeed& need) const;

  const Scene& scene() const { return scene_; }
  GlContext* gl() const { return gl_; }
  ShaderLibrary& shaders() const;  // GL resources only
  const std::vector<float>& frameTimes() const { return frameTimes_; }
  int threads() const { return threads_; }
  float time() const { return time_; }
  bool dynamic() const;  // the scene has dynamic meshes

  // What was allocated, as SceneNeeds::names() spells it (the G-buffer, a
  // render target, is the sample loop's: it adds that name).
  std::vector<std::string> built() const;
  // Each resource's stats under its kind's statsKey, with "rebuilt_this_frame"
  // (whether the last update changed it); call after the image (they may read back).
  void addStats(nlohmann::json& extra);
  // The bytes the built resources report (the "bytes" of what addStats writes), all together.
  double bytes();

 private:
  struct Entry {
    ResourceNeed need;
    const ResourceKind* kind;
    std::unique_ptr<Resource> resource;
    bool changed = false;  // in the update or relight under way (or the last one)
    bool rebuilt = false;  // by the last update (relights aside)
  };
  void* find(const std::type_info& t, const ResourceNeed* need, bool required) const;
  void placeLights();
  void relightAll(Profiler& profiler);
  const Scene& scene_;
  SceneNeeds needs_;
  GlContext* gl_;
  ShaderLibrary* shaders_;
  std::vector<float> frameTimes_;
  int threads_;
  std::vector<Entry> entries_;  // the needs' closure, dependencies first
  bool first_ = true, lightsChanged_ = false;
  std::vector<std::string> adopted_;
  float time_ = 0;
  std::unique_ptr<Emitters> emitters_;  // the GL lights' area lights
  std::vector<Light> lights_;
  bool sampleLights_ = false;  // lights_ follow the sample (area lights on GL resources)
  long long lightsKey_ = -1;   // (seed, k) of the lights placed; −1: none yet
};

}  // namespace vgi
