#include "traverse/embree_tracer.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace vgi {

namespace {
void onEmbreeError(void* user, RTCError code, const char* str) {
  *static_cast<std::string*>(user) = "Embree error " + std::to_string(int(code)) + ": " + (str ? str : "");
}
}  // namespace

EmbreeTracer::EmbreeTracer(const FlatScene& s) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) fail("Embree: rtcNewDevice failed (error ", int(rtcGetDeviceError(nullptr)), ")");
  rtcSetDeviceErrorFunction(device_, onEmbreeError, &error_);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  const size_t n = s.triangleCount();
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  if (!v || !idx) fail("Embree: cannot allocate buffers for ", n, " triangles: ", error_);
  for (size_t i = 0; i < 3 * n; ++i) {
    v[3 * i + 0] = s.positions[i].x;
    v[3 * i + 1] = s.positions[i].y;
    v[3 * i + 2] = s.positions[i].z;
    idx[i] = unsigned(i);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene_, geom, 0);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  if (!error_.empty()) fail("Embree: building the scene failed: ", error_);
}

EmbreeTracer::~EmbreeTracer() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

namespace {
// Embree asserts (aborts the process) on a ray outside RTCRay's valid range: origin and direction
// components within ±1.844e18 and finite, tnear and tfar not NaN. Every maker of rays keeps them in
// range (the scene's range checks); a ray that still is not is a bug, reported on the caller's thread.
constexpr float kEmbreeLarge = 1.844e18f;
RTCRay makeRay(glm::vec3 o, glm::vec3 d, float tnear, float tfar) {
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(o[k]) <= kEmbreeLarge) || !(std::abs(d[k]) <= kEmbreeLarge) || std::isnan(tnear) ||
        std::isnan(tfar))
      fail("internal: a ray outside Embree's range: origin (", o.x, ", ", o.y, ", ", o.z, "), direction (",
           d.x, ", ", d.y, ", ", d.z, "), t in [", tnear, ", ", tfar, "]");
  RTCRay r;
  r.org_x = o.x;
  r.org_y = o.y;
  r.org_z = o.z;
  r.dir_x = d.x;
  r.dir_y = d.y;
  r.dir_z = d.z;
  r.tnear = tnear;
  r.tfar = tfar;
  r.time = 0;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
  return r;
}
}  // namespace

TriangleHit EmbreeTracer::firstHit(glm::vec3 o, glm::vec3 d, float tnear, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray = makeRay(o, d, tnear, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  TriangleHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.triangle = int(rh.hit.primID);
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  return h;
}

bool EmbreeTracer::occluded(glm::vec3 o, glm::vec3 d, float tnear, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = makeRay(o, d, tnear, tfar);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

}  // namespace vgi
