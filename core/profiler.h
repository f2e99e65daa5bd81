// Named passes timed on the CPU and, when a GL context is current, on the GPU
// with timestamp-query pairs. Queries come from a pool that is recycled as
// results arrive (a ring: nothing stalls while frames are in flight); resolve()
// waits for the rest at the end.
#pragma once
#include <chrono>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace vgi {

class Profiler {
 public:
  explicit Profiler(bool gpu) : gpu_(gpu) {}
  ~Profiler();
  Profiler(const Profiler&) = delete;
  Profiler& operator=(const Profiler&) = delete;

  class Scope {
   public:
    Scope(Profiler& p, std::string name);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    Profiler& p_;
    std::string name_;
    unsigned queryBegin_ = 0;
    std::chrono::steady_clock::time_point start_;
  };
  Scope scope(const std::string& name) { return Scope(*this, name); }

  // Adds time measured elsewhere (e.g. a CPU renderer's phases).
  void addCpu(const std::string& name, double ms);
  // Collects GPU results; wait=true blocks until every query has one.
  void resolve(bool wait);

  // pass → GPU ms when measured on the GPU, else CPU ms (sums over calls).
  nlohmann::json timingsMs() const;
  nlohmann::json cpuTimingsMs() const;
  nlohmann::json callCounts() const;
  double totalMs() const;  // sum of timingsMs()

 private:
  struct Pending {
    std::string name;
    unsigned begin, end;
  };
  unsigned takeQuery();
  bool gpu_;
  std::vector<unsigned> freeQueries_, allQueries_;
  std::vector<Pending> pending_;
  std::map<std::string, double> gpuMs_, cpuMs_;
  std::map<std::string, long> calls_;
  std::vector<std::string> order_;
};

}  // namespace vgi
