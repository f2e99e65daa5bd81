// Runs the `vgi` command as a user does: exit status and everything it printed.
#pragma once
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "test_util.h"

namespace vgi::test {

struct CliRun {
  int code;  // the exit status; -1 when killed by a signal (a crash)
  std::string output;
};

// A shell command line, its exit status and its output (stdout and stderr).
inline CliRun shell(const std::string& command) {
  std::string cmd = command + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// `vgi ARGS`; `args` go through the shell (quote what needs it).
inline CliRun vgi(const std::string& args) { return shell(std::string(VGI_BINARY) + " " + args); }

inline std::string tmp(const std::string& name) { return testing::TempDir() + "/" + name; }

}  // namespace vgi::test
