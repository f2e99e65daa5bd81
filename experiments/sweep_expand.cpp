// `vgi sweep`, an experiment's methods expanded: each method's grid into points (scenes × the
// parameters' combinations), each point with its reference render and its counterpart's convergence
// curve on the point's device (experiments/sweep.h). Renders are named by a hash of their arguments,
// so one reference or curve shared by several points is rendered once.
#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "core/hash.h"
#include "core/json_text.h"
#include "experiments/compare.h"
#include "experiments/sweep_detail.h"
#include "illum/framework/method.h"
#include "illum/run/render_job.h"

namespace vgi::sweep_detail {

namespace {

std::string hashId(const std::vector<std::string>& parts) {
  uint64_t h = kFnv1aOffset;
  const unsigned char separator = 0xffu;
  for (auto& p : parts) h = fnv1a(&separator, 1, fnv1a(p, h));
  char buf[20];
  std::snprintf(buf, sizeof buf, "%012llx", (unsigned long long)(h & 0xffffffffffffull));
  return buf;
}

// The render options of points, references and counterpart curves.
RenderOptions sweepRenderOptions(const Experiment& e, const std::string& scene, const std::string& method,
                                 const std::vector<std::string>& set, int spp,
                                 const std::vector<std::string>& aovs, const std::vector<int>& checkpoints,
                                 uint32_t seed, double timeLimitS) {
  RenderOptions o;
  o.scene = scene;
  o.method = method;
  o.methodGiven = true;
  o.set = set;
  o.width = e.width;
  o.height = e.height;
  o.spp = spp;
  o.seed = seed;
  o.progress = false;
  o.aovs = aovs;
  o.checkpoints = checkpoints;
  o.timeLimitS = timeLimitS;
  const Experiment::Animation& a = e.animation.at(scene);
  o.frames = a.frames;
  o.timeStep = a.timeStep;
  o.time = a.time;
  return o;
}

SweepRender makeRender(const std::string& dir, const std::string& kind, const std::string& name,
                       const RenderOptions& options) {
  SweepRender r;
  std::vector<std::string> args = {"render"};
  for (std::string& a : renderArgs(options)) args.push_back(std::move(a));
  r.id = name + "-" + hashId(args);
  r.dir = dir + "/" + kind + "/" + r.id;
  r.stem = r.dir + (kind == "references" ? "/ref.exr" : "/render.exr");
  args.insert(args.end(), {"-o", r.stem});
  r.args = std::move(args);
  r.options = options;
  return r;
}

// The grid's axes: every key's values as text, keys in the file's (sorted) order; `combos` their
// product, refused beyond 10000.
using GridAxes = std::vector<std::pair<std::string, std::vector<std::string>>>;
GridAxes readGrid(const nlohmann::json& grid, const std::string& where, size_t& combos) {
  GridAxes axes;
  for (auto& [k, v] : grid.items()) {
    if (!v.is_array() || v.empty())
      fail("experiment: ", where, ".grid.", k, " = ", v.dump(), " must be a non-empty list of values");
    std::vector<std::string> values;
    for (auto& x : v) values.push_back(paramText(x, where + ".grid." + k));
    axes.emplace_back(k, values);
  }
  combos = 1;
  for (auto& a : axes) {
    // Checked before multiplying: 16 keys of 16 values would wrap a size_t to 0.
    if (combos > 10000 / a.second.size())
      fail("experiment: ", where, ".grid expands to more than 10000 points (", axes.size(),
           " keys; at most 10000 combinations)");
    combos *= a.second.size();
  }
  return axes;
}

// Where a point's reference comes from: the method's own "reference" (a method and its set, or
// another method's counterpart), the experiment's "reference.method", or the method's registry
// counterpart (the default).
struct ReferenceChoice {
  std::string method;
  std::vector<std::string> set, aovs;
  std::vector<std::string> full;  // a registry counterpart's full reference (Counterpart::full), else empty
  bool counterpart = false;       // the reference is a registry counterpart (its own or counterpart_of)
};
ReferenceChoice chooseReference(const Experiment& e, const nlohmann::json& ref, const nlohmann::json& mref,
                                const std::string& where, const MethodInfo& info, const RenderOptions& o,
                                const nlohmann::json& resolved) {
  const std::string& method = o.method;
  ReferenceChoice rc;
  std::string& rmethod = rc.method;
  std::vector<std::string>& rset = rc.set;
  std::vector<std::string>& raovs = rc.aovs;
  if (mref.contains("method")) {
    rmethod = stringAt(mref, "method", where + ".reference.method");
    findMethod(rmethod, "experiment " + where + ".reference.method");
    const nlohmann::json refSet = mref.value("set", nlohmann::json::object());
    if (!refSet.is_object()) fail("experiment: ", where, ".reference.set must be an object of parameters");
    for (auto& [k, v] : refSet.items()) rset.push_back(k + "=" + paramText(v, where + ".reference.set." + k));
    raovs = e.aovs;
  } else if (mref.contains("variant")) {
    // The point itself with a few parameters changed (one stage made exact: an error split).
    const nlohmann::json& variant = mref["variant"];
    if (!variant.is_object() || variant.empty())
      fail("experiment: ", where, ".reference.variant must be an object of the parameters to change");
    rmethod = method;
    for (const std::string& kv : o.set)
      if (!variant.contains(kv.substr(0, kv.find('=')))) rset.push_back(kv);
    for (auto& [k, v] : variant.items())
      rset.push_back(k + "=" + paramText(v, where + ".reference.variant." + k));
    raovs = e.aovs;
  } else if (mref.contains("counterpart_of")) {
    const std::string other = stringAt(mref, "counterpart_of", where + ".reference.counterpart_of");
    const MethodInfo& oi = findMethod(other, "experiment " + where + ".reference.counterpart_of");
    if (!oi.counterpart)
      fail("experiment: ", where, ".reference.counterpart_of: '", other, "' has no counterpart");
    RenderOptions oo = o;
    oo.method = other;
    oo.set.clear();
    const Counterpart cp = oi.counterpart(resolveParameters(oo));
    rmethod = cp.method;
    rset = cp.set;
    rc.full = cp.full;
    rc.counterpart = true;
    for (auto& a : e.aovs)
      if (std::find(cp.aovs.begin(), cp.aovs.end(), a) != cp.aovs.end()) raovs.push_back(a);
  } else if (ref.contains("method")) {
    rmethod = stringAt(ref, "method", "reference.method");
    findMethod(rmethod, "experiment reference.method");
    const nlohmann::json refSet = ref.value("set", nlohmann::json::object());
    if (!refSet.is_object()) fail("experiment: reference.set must be an object of parameters");
    for (auto& [k, v] : refSet.items()) rset.push_back(k + "=" + paramText(v, "reference.set." + k));
    raovs = e.aovs;
  } else {
    if (!info.counterpart)
      fail("experiment: ", where, ": method '", method,
           "' has no exact counterpart; give "
           "\"reference\": {\"method\": …}");
    const Counterpart cp = info.counterpart(resolved);
    rmethod = cp.method;
    rset = cp.set;
    rc.full = cp.full;
    rc.counterpart = true;
    for (auto& a : e.aovs)
      if (std::find(cp.aovs.begin(), cp.aovs.end(), a) != cp.aovs.end()) raovs.push_back(a);
  }
  return rc;
}

// The index of reference render `r` in e.references: the one already there with its id, or `r`
// added, its parameters checked (a refusal names `what`).
size_t referenceIndex(Experiment& e, const SweepRender& r, const std::string& what) {
  auto same = std::find_if(e.references.begin(), e.references.end(),
                           [&](const SweepRender& x) { return x.id == r.id; });
  if (same != e.references.end()) return size_t(same - e.references.begin());
  try {
    resolveParameters(r.options);
  } catch (const Error& ex) {
    fail("experiment: ", what, ": ", ex.what());
  }
  e.references.push_back(r);
  return e.references.size() - 1;
}

// Registers the reference render of point `pt` (one per distinct render) and its convergence curve:
// the same integral with the next seed, against the reference, on the point's device (reference's GL
// twin for a GL method, unless reference.device is "cpu"), what each point's equal-error time is read
// off. The reference image may come from either device (the same integral). `curveMethods` caches
// the device choice per method and reference.
void addReference(Experiment& e, SweepPoint& pt, const RenderOptions& o, const ReferenceChoice& rc,
                  int refSpp, const std::string& where,
                  std::map<std::string, CounterpartChoice>& curveMethods) {
  const std::string &scene = o.scene, &method = o.method, &dir = e.dir;
  const std::string& rmethod = rc.method;
  const std::vector<std::string>&rset = rc.set, &raovs = rc.aovs;
  const SweepRender r = makeRender(dir, "references", rmethod,
                                   sweepRenderOptions(e, scene, rmethod, rset, refSpp, raovs, {}, e.seed, 0));
  pt.reference = referenceIndex(e, r, "reference of " + where + " (" + rmethod + " on " + scene + ")");
  // Its own convergence: the same integral with the next seed, against the reference,
  // on the point's device (reference's GL twin for a GL method, unless reference.device
  // is "cpu"): what each point's equal-error time is read off. The reference image may
  // come from either device (the same integral).
  if (!e.curveCounts.empty()) {
    const std::string key = method + "\n" + r.id;
    auto known = curveMethods.find(key);
    if (known == curveMethods.end()) {
      CounterpartChoice choice;
      try {
        choice = counterpartOnDevice(o, Counterpart{rmethod, rset, raovs}, e.exactDevice);
      } catch (const Error& ex) {
        fail("experiment: 'reference.device' = \"cpu\": the curve of ", where, " (", rmethod, " on ", scene,
             "): ", ex.what());
      }
      // "same", written in the file, is a demand: a curve that must leave the method's device is refused.
      if (e.exactDeviceGiven && e.exactDevice == ExactDevice::Same && !choice.sameDevice)
        fail("experiment: 'reference.device' = \"same\", but the curve of ", where, " (", method,
             ", counterpart ", rmethod, ") cannot run on the method's device: ", choice.note,
             " (say \"cpu\", or leave 'device' out to accept either)");
      known = curveMethods.emplace(key, choice).first;
    }
    const std::string& cmethod = known->second.counterpart.method;
    const std::vector<int> below(e.curveCounts.begin(), e.curveCounts.end() - 1);
    const SweepRender curve = makeRender(
        dir, "curves", cmethod,
        sweepRenderOptions(e, scene, cmethod, rset, e.curveCounts.back(), raovs, below, e.seed + 1, 0));
    auto c = std::find_if(e.curves.begin(), e.curves.end(),
                          [&](const SweepRender& x) { return x.id == curve.id; });
    if (c == e.curves.end()) {
      e.curves.push_back(curve);
      e.curveReference.push_back(pt.reference);
      e.curveChoice.push_back(known->second);
      c = e.curves.end() - 1;
    }
    pt.curve = int(c - e.curves.begin());
  }
}

// "split": the full reference of point `pt` (Counterpart::full of the method whose counterpart
// the reference is, on the reference's device, seed + kFullReferenceSeedOffset), shared like
// the references.
void addFullReference(Experiment& e, SweepPoint& pt, const RenderOptions& o, const ReferenceChoice& rc,
                      int refSpp, const std::string& where) {
  if (rc.full.empty())
    fail("experiment: 'reference.split': ", where, " (", o.method,
         "): its counterpart's registry row names no full reference");
  SweepRender r = makeRender(e.dir, "references", rc.method,
                             sweepRenderOptions(e, o.scene, rc.method, rc.full, refSpp, rc.aovs, {},
                                                e.seed + kFullReferenceSeedOffset, 0));
  pt.full =
      int(referenceIndex(e, r, "full reference of " + where + " (" + rc.method + " on " + o.scene + ")"));
}

}  // namespace

void expandMethod(const nlohmann::json& j, size_t mi, const nlohmann::json& ref, int refSpp, Experiment& e,
                  ExpandState& st) {
  const std::string& dir = e.dir;
  std::map<std::string, CounterpartChoice>& curveMethods = st.curveMethods;
  std::set<std::string>& written = st.written;
  const nlohmann::json& m = j["methods"][mi];
  const std::string where = "methods[" + std::to_string(mi) + "]";
  checkKeys(m, where, {"method", "label", "set", "grid", "spp", "seed", "reference"});
  if (!m.contains("method") || !m["method"].is_string())
    fail("experiment: ", where, " has no \"method\" name");
  const std::string method = m["method"].get<std::string>();
  const MethodInfo& info = findMethod(method, "experiment " + where + ".method");
  const int spp = m.contains("spp") ? intIn(m["spp"], where + ".spp", 1, 1 << 20) : e.spp;
  const uint32_t seed = m.contains("seed") ? uint32_t(intIn(m["seed"], where + ".seed", 0, 1 << 30)) : e.seed;
  std::vector<int> checkpoints;
  for (int k : e.checkpoints)
    if (k < spp) checkpoints.push_back(k);
  // Its own reference: another method's counterpart (shared with that method's points), or a method.
  const nlohmann::json mref = m.value("reference", nlohmann::json::object());
  checkKeys(mref, where + ".reference", {"counterpart_of", "method", "set", "variant"});
  if (m.contains("reference") &&
      int(mref.contains("counterpart_of")) + int(mref.contains("method")) + int(mref.contains("variant")) !=
          1)
    fail("experiment: ", where, ".reference = ", jsonExcerpt(mref),
         " needs one of \"counterpart_of\", \"method\" or \"variant\"");
  if (mref.contains("set") && !mref.contains("method"))
    fail("experiment: ", where, ".reference.set goes with \"method\" (a variant's changes are its value)");
  std::vector<std::string> fixed;
  const nlohmann::json set = m.value("set", nlohmann::json::object()),
                       grid = m.value("grid", nlohmann::json::object());
  for (const auto* o : {&set, &grid})
    if (!o->is_object())
      fail("experiment: ", where, o == &set ? ".set" : ".grid", " must be an object of parameters, not ",
           o->dump());
  for (auto& [k, v] : set.items()) fixed.push_back(k + "=" + paramText(v, where + ".set." + k));
  size_t combos = 1;
  const GridAxes axes = readGrid(grid, where, combos);
  for (const std::string& scene : e.scenes)
    for (size_t c = 0; c < combos; ++c) {
      SweepPoint pt;
      pt.scene = scene;
      pt.method = method;
      pt.label = stringAt(m, "label", where + ".label", method);
      std::vector<std::string> set = fixed;
      size_t rest = c;
      pt.params = nlohmann::json::object();
      for (auto& [k, values] : axes) {
        const std::string& v = values[rest % values.size()];
        rest /= values.size();
        set.push_back(k + "=" + v);
        pt.params[k] = v;
      }
      RenderOptions o = sweepRenderOptions(e, scene, method, set, spp, {}, checkpoints, seed, e.timeBudgetS);
      pt.seed = seed;
      nlohmann::json resolved;
      std::vector<std::string> outputs;
      try {
        resolved = resolveParameters(o, &outputs);  // unknown or out-of-range parameters, a scene that fails
      } catch (const Error& ex) {
        fail("experiment: ", where, " (", method, " on ", scene, ", ", pt.params.dump(), "): ", ex.what());
      }
      written.insert(outputs.begin(), outputs.end());
      // Only the outputs this method writes are asked of it.
      std::vector<std::string> aovs;
      for (auto& a : e.aovs)
        if (std::find(outputs.begin(), outputs.end(), a) != outputs.end()) aovs.push_back(a);
      o.aovs = aovs;
      pt.render = makeRender(dir, "points", method, o);
      pt.spp = spp;
      // The reference.
      if (ref.contains("file") && !m.contains("reference")) {
        pt.reference = 0;
      } else {
        const ReferenceChoice rc = chooseReference(e, ref, mref, where, info, o, resolved);
        addReference(e, pt, o, rc, refSpp, where, curveMethods);
        if (e.split && rc.counterpart) addFullReference(e, pt, o, rc, refSpp, where);
      }
      // With "seeds": the same point with the next seeds, against the same references.
      e.points.push_back(pt);
      for (int k = 1; k < e.seeds; ++k) {
        RenderOptions ok = o;
        ok.seed = pt.seed = seed + kSeedStride * uint32_t(k);
        pt.render = makeRender(dir, "points", method, ok);
        e.points.push_back(pt);
      }
    }
}

}  // namespace vgi::sweep_detail
