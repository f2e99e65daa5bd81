// KHR_debug as a test failure: every test fails when any GL context of the process reported an
// error or a high-severity debug message while it ran (on whichever driver the suite runs: llvmpipe,
// or zink with --gl zink), with the message naming the pass (core/gl_context.h). A test that raises an
// error on purpose takes it with GlContext::takeProcessErrors() and so owns it.
// The labels hold too: a test CTest runs with the label `unit` (VGI_TEST_LABEL, tests/CMakeLists.txt)
// fails when it made a GL context — the fast set stays free of the GL driver.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/gl_context.h"

namespace vgi {

namespace {

class GlErrorListener : public testing::EmptyTestEventListener {
  long contexts = 0;
  void OnTestStart(const testing::TestInfo&) override {
    GlContext::takeProcessErrors();
    contexts = GlContext::processContextCount();
  }
  // gtest calls the listeners' OnTestEnd in reverse order, while the test is still current: this
  // failure is the test's own, reported before the result printer writes its line.
  void OnTestEnd(const testing::TestInfo& t) override {
    for (const std::string& e : GlContext::takeProcessErrors()) ADD_FAILURE() << "KHR_debug: " << e;
    const char* label = std::getenv("VGI_TEST_LABEL");
    if (label && std::string(label) == "unit" && GlContext::processContextCount() != contexts)
      ADD_FAILURE() << t.test_suite_name() << "." << t.name()
                    << " is labelled unit but made a GL context: list it under gl (tests/CMakeLists.txt)";
  }
};

const bool registered = [] {
  testing::UnitTest::GetInstance()->listeners().Append(new GlErrorListener);
  return true;
}();

}  // namespace

}  // namespace vgi
