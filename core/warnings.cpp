#include "core/warnings.h"

#include <cstdio>
#include <mutex>
#include <set>

namespace vgi {

namespace {
std::mutex printedMutex;
std::set<std::string> printed;  // the process's warnings so far: stderr is the process's too
}  // namespace

void printWarning(const std::string& text) {
  std::lock_guard<std::mutex> lock(printedMutex);
  if (!printed.insert(text).second) return;
  std::fprintf(stderr, "vgi: warning: %s\n", text.c_str());
  std::fflush(stderr);
}

void printWarnings(const std::vector<std::string>& texts) {
  for (const std::string& t : texts) printWarning(t);
}

}  // namespace vgi
