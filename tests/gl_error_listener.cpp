// KHR_debug as a test failure: every test fails when any GL context of the process reported an
// error or a high-severity debug message while it ran (on whichever driver the suite runs: llvmpipe,
// or zink with --gl zink), with the message naming the pass (core/gl_context.h). A test that raises an
// error on purpose takes it with GlContext::takeProcessErrors() and so owns it.
#include <gtest/gtest.h>

#include "core/gl_context.h"

namespace vgi {

namespace {

class GlErrorListener : public testing::EmptyTestEventListener {
  void OnTestStart(const testing::TestInfo&) override { GlContext::takeProcessErrors(); }
  // gtest calls the listeners' OnTestEnd in reverse order, while the test is still current: this
  // failure is the test's own, reported before the result printer writes its line.
  void OnTestEnd(const testing::TestInfo&) override {
    for (const std::string& e : GlContext::takeProcessErrors()) ADD_FAILURE() << "KHR_debug: " << e;
  }
};

const bool registered = [] {
  testing::UnitTest::GetInstance()->listeners().Append(new GlErrorListener);
  return true;
}();

}  // namespace

}  // namespace vgi
