// The light-map face layout (C++, illum/light_maps.cpp) against the shared
// lookup functions the GLSL passes run (shaders/shared/light_maps.glsl): every
// point a light can see falls inside the face the lookup picks, and distances
// and texel sizes follow the face's projection.
#include "illum/resources/light_maps.h"

#include <random>

#include "test_util.h"

namespace vgi {

using namespace vgi::shared;

namespace {
Bounds cube(float half) {
  Bounds b;
  b.extend(glm::vec3(-half));
  b.extend(glm::vec3(half));
  return b;
}

Light makeLight(LightType type, glm::vec3 dir, float coneDeg) {
  Light l;
  l.type = type;
  l.position = glm::vec3(0.2f, 0.3f, -0.1f);
  l.direction = dir;
  l.coneHalfAngleDeg = coneDeg;
  return l;
}
}  // namespace

TEST(LightMaps, EveryVisiblePointProjectsIntoTheFaceTheLookupPicks) {
  const Bounds b = cube(2.0f);
  const glm::vec3 down = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  std::vector<Light> lights = {makeLight(LightType::Point, down, 90), makeLight(LightType::Spot, down, 40),
                               makeLight(LightType::Spot, down, 80),
                               makeLight(LightType::Directional, down, 90)};
  LightFaceLayout layout = layoutLightFaces(lights, b, 512);
  ASSERT_EQ(layout.ranges.size(), 4u);
  EXPECT_EQ(layout.ranges[0].y, 6);  // point: cube
  EXPECT_EQ(layout.ranges[1].y, 1);  // 40° spot: one face
  EXPECT_EQ(layout.ranges[2].y, 6);  // 80° spot: cube
  EXPECT_EQ(layout.ranges[3].y, 1);  // directional: one orthographic face
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  int checked[4] = {0, 0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    for (size_t l = 0; l < lights.size(); ++l) {
      const glm::ivec4 r = layout.ranges[l];
      if (lights[l].type == LightType::Spot && glm::dot(glm::normalize(p - lights[l].position), down) <
                                                   std::cos(glm::radians(lights[l].coneHalfAngleDeg)))
        continue;  // outside the cone: never lit, never looked up
      int f = lightMapFace(layout.faces[size_t(r.x)], r.x, r.y, p);
      ASSERT_GE(f, r.x);
      ASSERT_LT(f, r.x + r.y);
      const LightFace& face = layout.faces[size_t(f)];
      glm::vec2 uv = lightMapUv(face, p);
      // In front of the face (a point behind it projects mirrored, possibly inside [0,1]²).
      glm::vec4 clip = face.viewProj * glm::vec4(p, 1.0f);
      EXPECT_GT(clip.w, 0.0f) << "light " << l << " face " << f;
      EXPECT_TRUE(uv.x >= -1e-4f && uv.x <= 1.0001f && uv.y >= -1e-4f && uv.y <= 1.0001f)
          << "light " << l << " face " << f << " uv " << uv.x << "," << uv.y;
      float d = lightMapDistance(face, p);
      if (lights[l].type == LightType::Directional) {
        EXPECT_GT(d, 0.0f);  // the map's plane lies before the scene
        EXPECT_FLOAT_EQ(lightMapTexelWorld(face, d), lightMapTexelWorld(face, 1.0f));
      } else {
        EXPECT_NEAR(d, glm::length(p - lights[l].position), 1e-5f);
        EXPECT_NEAR(lightMapTexelWorld(face, 2.0f * d), 2.0f * lightMapTexelWorld(face, d), 1e-6f);
      }
      ++checked[l];
    }
  }
  for (int c : checked) EXPECT_GT(c, 500);
}

// Cube faces a spot cannot light are not drawn: every direction of such a
// face (a 33×33 lattice, edges and corners included) lies outside the cone;
// the up face of a downward 90° spot (the Cornell box's light) is one.
TEST(LightMaps, CubeFacesOutsideASpotConeAreNotDrawn) {
  const Bounds b = cube(2.0f);
  const glm::vec3 tilted = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  struct Case {
    Light light;
    int drawn;
  };
  const Case cases[] = {{makeLight(LightType::Spot, {0, -1, 0}, 90), 5},
                        {makeLight(LightType::Spot, {1, 0, 0}, 61), 5},
                        {makeLight(LightType::Spot, tilted, 70), 5},
                        {makeLight(LightType::Spot, tilted, 135), 6},
                        {makeLight(LightType::Point, {0, -1, 0}, 90), 6}};
  for (const Case& c : cases) {
    LightFaceLayout layout = layoutLightFaces({c.light}, b, 64);
    ASSERT_EQ(layout.faces.size(), 6u);
    ASSERT_EQ(layout.drawn.size(), 6u);
    int drawn = 0;
    const float cosCone = std::cos(glm::radians(c.light.coneHalfAngleDeg));
    for (int f = 0; f < 6; ++f) {
      drawn += layout.drawn[size_t(f)] ? 1 : 0;
      if (layout.drawn[size_t(f)]) continue;
      const glm::vec3 axis = glm::vec3(layout.faces[size_t(f)].axisTexel);
      const glm::vec3 u = std::abs(axis.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0),
                      v = glm::cross(axis, u);
      for (int i = 0; i <= 32; ++i)
        for (int j = 0; j <= 32; ++j) {
          glm::vec3 d = glm::normalize(axis + (i / 16.0f - 1.0f) * u + (j / 16.0f - 1.0f) * v);
          if (i % 32 && j % 32) {  // (edges are shared with a neighbour)
            ASSERT_EQ(cubeFaceIndex(d), f);
          }
          EXPECT_LT(glm::dot(d, glm::normalize(c.light.direction)), cosCone) << "face " << f;
        }
    }
    EXPECT_EQ(drawn, c.drawn) << "cone " << c.light.coneHalfAngleDeg;
  }
  EXPECT_FALSE(layoutLightFaces({cases[0].light}, b, 64).drawn[2]);  // +y, GL's face order
}

// The receiver-plane distance at a texel centre equals the exact (double)
// distance along the ray through that centre to the plane, for points on
// planes lit from steep to grazing (down to cos 0.02), on perspective (cube,
// single) and orthographic faces.
TEST(LightMaps, PlaneDistanceAtTexelCentreIsExact) {
  const Bounds b = cube(1.0f);
  const glm::vec3 down = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  std::vector<Light> lights = {makeLight(LightType::Point, down, 90), makeLight(LightType::Spot, down, 40),
                               makeLight(LightType::Directional, down, 90)};
  lights[0].position = lights[1].position = glm::vec3(0.1f, 0.9f, 0.05f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.8f, 0.8f);
  int checked = 0;
  for (size_t l = 0; l < lights.size(); ++l) {
    LightFaceLayout layout = layoutLightFaces({lights[l]}, b, 1024);
    for (int i = 0; i < 3000; ++i) {
      glm::vec3 p(u(rng), u(rng) - 0.2f, u(rng));
      glm::vec3 toLight = l == 2 ? -down : glm::normalize(lights[l].position - p);
      // A plane through p whose normal makes cos = c with the light direction.
      float c = std::pow(10.0f, -1.7f + 1.7f * float(i % 100) / 99.0f);
      glm::vec3 side = glm::normalize(glm::cross(toLight, glm::vec3(0.3f, 0.5f, 0.8f)));
      glm::vec3 ng = c * toLight + std::sqrt(1.0f - c * c) * side;
      const int f = layout.faces.size() == 6 ? cubeFaceIndex(p - lights[l].position) : 0;
      const LightFace& face = layout.faces[size_t(f)];
      glm::vec2 uv = lightMapUv(face, p);
      if (uv.x < 0 || uv.y < 0 || uv.x >= 1 || uv.y >= 1) continue;
      glm::vec2 centre = lightMapTexelCentre(uv, 1024.0f);
      float got = lightMapPlaneDistance(face, centre, p, ng);
      glm::dmat4 inv = glm::inverse(glm::dmat4(face.viewProj));
      glm::dvec4 nearP = inv * glm::dvec4(centre.x * 2.0 - 1.0, centre.y * 2.0 - 1.0, -1.0, 1.0);
      glm::dvec4 farP = inv * glm::dvec4(centre.x * 2.0 - 1.0, centre.y * 2.0 - 1.0, 1.0, 1.0);
      glm::dvec3 o = glm::dvec3(nearP) / nearP.w, d = glm::normalize(glm::dvec3(farP) / farP.w - o);
      double t = glm::dot(glm::dvec3(p) - o, glm::dvec3(ng)) / glm::dot(d, glm::dvec3(ng));
      glm::dvec3 x = o + d * t;
      double expect = l == 2 ? glm::dot(x - glm::dvec3(lightFaceEye(face)), glm::dvec3(down))
                             : glm::length(x - glm::dvec3(lights[l].position));
      const float texel = lightMapTexelWorld(face, lightMapDistance(face, p));
      // It is never farther than the point itself by more than the texel's
      // footprint on the plane, and equals the exact value to 1e-4 texel / cos.
      ASSERT_NEAR(got, expect, 1e-3 * texel / c + 1e-6) << "light " << l << " cos " << c;
      ++checked;
    }
  }
  EXPECT_GT(checked, 6000);
}

// The texel areas of a face, summed over the texels that see a plane, are
// the plane's area inside the face's frustum: (2h·tan(fov/2))² below a spot
// or a cube face, (2r)²/cos θ for a directional light at θ to the plane.
TEST(LightMaps, TexelAreasSumToTheSurfaceTheFaceSees) {
  const Bounds b = cube(1.0f);
  const float h = 0.7f;
  const int n = 256;
  struct Case {
    LightType type;
    glm::vec3 direction;
    float cone;
    int face;
  };
  const glm::vec3 slanted = glm::normalize(glm::vec3(0.5f, -1.0f, 0.2f));
  for (const Case& k : {Case{LightType::Spot, {0, -1, 0}, 40, 0}, Case{LightType::Point, {0, -1, 0}, 90, 3},
                        Case{LightType::Directional, slanted, 90, 0}}) {
    Light light = makeLight(k.type, k.direction, k.cone);
    light.position = glm::vec3(0.0f, h, 0.0f);
    const LightFaceLayout layout = layoutLightFaces({light}, b, n);
    const LightFace& face = layout.faces[size_t(k.face)];
    const bool ortho = face.eyeOrtho.w > 0.5f;
    double sum = 0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec2 c((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
        const glm::vec4 a = face.rayUnproject * glm::vec4(c.x * 2.0f - 1.0f, c.y * 2.0f - 1.0f, -1.0f, 1.0f);
        const glm::vec3 onRay = glm::vec3(a) / a.w;
        const glm::vec3 o = ortho ? onRay : lightFaceEye(face);
        const glm::vec3 d = ortho ? glm::vec3(face.axisTexel) : glm::normalize(onRay - o);
        ASSERT_LT(d.y, 0.0f);
        const glm::vec3 p = o + d * (-o.y / d.y);  // on the plane y = 0
        sum += lightMapTexelArea(face, p, glm::vec3(0, 1, 0));
      }
    double expect;
    if (k.type == LightType::Directional) {
      const double side = double(face.axisTexel.w) * n;
      expect = side * side / -double(slanted.y);
    } else {
      const double t = double(face.axisTexel.w) * n / 2.0;  // tan(fov/2)
      expect = (2.0 * h * t) * (2.0 * h * t);
    }
    EXPECT_NEAR(sum / expect, 1.0, 1e-3) << "light type " << int(k.type);
  }
}

TEST(LightMaps, BackProjectionEpsilonFollowsTheRule) {
  EXPECT_FLOAT_EQ(backProjectionEpsilon(0.1f, 0.01f, 1.0f), 0.1f);   // voxel-bound
  EXPECT_FLOAT_EQ(backProjectionEpsilon(0.01f, 0.05f, 0.5f), 0.1f);  // texel / cos α
  EXPECT_FLOAT_EQ(backProjectionEpsilon(0.01f, 0.05f, 0.0f), 0.5f);  // cos α clamped at 0.1
}

}  // namespace vgi
