#include "core/params.h"

#include "test_util.h"

namespace vgi {
using test::expectError;

TEST(Params, DefaultsAreResolvedAndDocumented) {
  ParamSet p;
  EXPECT_EQ(p.getInt("rays", 16, "rays per pixel", 1, 1024), 16);
  EXPECT_FLOAT_EQ(p.getFloat("radius", 0.5f, "ray length", 0.0f, 10.0f), 0.5f);
  EXPECT_EQ(p.resolved()["rays"], 16);
  ASSERT_EQ(p.docs().size(), 2u);
  EXPECT_EQ(p.docs()[0].key, "rays");
  p.checkAllUsed("test");
}

TEST(Params, ValuesParseAndRangesAreEnforced) {
  ParamSet p;
  p.setFromString("rays=32");
  p.setFromString("env=off");
  p.setFromString("tracer=dda");
  EXPECT_EQ(p.getInt("rays", 16, "", 1, 1024), 32);
  EXPECT_FALSE(p.getBool("env", true, ""));
  EXPECT_EQ(p.getString("tracer", "hierarchical", "", {"hierarchical", "dda"}), "dda");
  p.checkAllUsed("test");

  ParamSet q;
  q.setFromString("rays=0");
  expectError([&] { q.getInt("rays", 16, "", 1, 1024); }, {"rays", "0", "out of range"});
  ParamSet r;
  r.setFromString("radius=abc");
  expectError([&] { r.getFloat("radius", 1, "", 0, 10); }, {"radius", "abc"});
  ParamSet s;
  s.setFromString("radius=nan");
  expectError([&] { s.getFloat("radius", 1, "", 0, 10); }, {"radius", "nan"});
  ParamSet t;
  t.setFromString("tracer=octree");
  expectError([&] { t.getString("tracer", "dda", "", {"hierarchical", "dda"}); }, {"tracer", "octree"});
  ParamSet u;
  u.setFromString("rays=12x");
  expectError([&] { u.getInt("rays", 1, "", 1, 100); }, {"rays", "12x"});
}

TEST(Params, UnreadKeysAreErrors) {
  ParamSet p;
  p.setFromString("radiuss=0.3");
  p.getFloat("radius", 0.1f, "", 0, 1);
  expectError([&] { p.checkAllUsed("method 'x'"); }, {"radiuss=0.3", "method 'x'", "known: radius"});
  expectError([&] { p.setFromString("novalue"); }, {"novalue", "key=value"});
}

}  // namespace vgi
