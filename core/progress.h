// Terminal progress bar for long renders, and a Ctrl-C flag so a render can stop
// early and still write what it accumulated.
#pragma once
#include <atomic>
#include <chrono>
#include <string>

namespace vgi {

// Installs a SIGINT handler that sets the flag (a second Ctrl-C kills as usual).
void installInterruptHandler();
bool interruptRequested();
void resetInterrupt();
// For tests: behave as if Ctrl-C had been pressed.
void requestInterrupt();

class ProgressBar {
 public:
  // Draws only when stderr is a terminal.
  ProgressBar(std::string label, long total);
  ~ProgressBar();
  void advance(long n = 1);
  void finish();

 private:
  void draw(bool force);
  std::string label_;
  long total_;
  std::atomic<long> done_{0};
  bool enabled_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
  bool finished_ = false;
};

}  // namespace vgi
