#include "core/progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <mutex>

namespace vgi {

namespace {
std::atomic<bool> g_interrupt{false};
extern "C" void onSigint(int) {
  g_interrupt.store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C terminates immediately
}
std::mutex g_drawMutex;
}  // namespace

void installInterruptHandler() { std::signal(SIGINT, onSigint); }
bool interruptRequested() { return g_interrupt.load(std::memory_order_relaxed); }
void resetInterrupt() { g_interrupt.store(false); }
void requestInterrupt() { g_interrupt.store(true); }

ProgressBar::ProgressBar(std::string label, long total)
    : label_(std::move(label)), total_(total > 0 ? total : 1), enabled_(isatty(2)) {
  start_ = lastDraw_ = std::chrono::steady_clock::now();
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::advance(long n) {
  done_ += n;
  if (enabled_) draw(false);
}

void ProgressBar::draw(bool force) {
  std::lock_guard<std::mutex> lock(g_drawMutex);
  auto now = std::chrono::steady_clock::now();
  if (!force && now - lastDraw_ < std::chrono::milliseconds(200)) return;
  lastDraw_ = now;
  double f = double(done_) / double(total_);
  if (f > 1) f = 1;
  double el = std::chrono::duration<double>(now - start_).count();
  double eta = f > 0 ? el / f - el : 0;
  int w = 30, fill = int(f * w);
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%  %.1fs elapsed, %.1fs left ", label_.c_str(), fill,
               "##############################", w - fill, "", 100 * f, el, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (finished_) return;
  finished_ = true;
  if (enabled_) {
    draw(true);
    std::fprintf(stderr, "\n");
  }
}

}  // namespace vgi
