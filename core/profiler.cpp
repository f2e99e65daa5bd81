#include "core/profiler.h"

#include <glad/gl.h>

#include <nlohmann/json.hpp>

namespace vgi {

Profiler::~Profiler() {
  if (gpu_ && !allQueries_.empty()) glDeleteQueries(GLsizei(allQueries_.size()), allQueries_.data());
}

unsigned Profiler::takeQuery() {
  if (freeQueries_.empty()) {
    resolve(false);
    if (freeQueries_.empty()) {
      GLuint q[16];
      glGenQueries(16, q);
      for (GLuint x : q) {
        freeQueries_.push_back(x);
        allQueries_.push_back(x);
      }
    }
  }
  unsigned q = freeQueries_.back();
  freeQueries_.pop_back();
  return q;
}

Profiler::Scope::Scope(Profiler& p, std::string name) : p_(p), name_(std::move(name)) {
  if (p_.gpu_) {
    // A KHR_debug group per pass: the context's callback names the pass in every error it reports,
    // and GPU debuggers (RenderDoc, Nsight) show the passes by name.
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name_.c_str());
    queryBegin_ = p_.takeQuery();
    glQueryCounter(queryBegin_, GL_TIMESTAMP);
  }
  start_ = std::chrono::steady_clock::now();
}

Profiler::Scope::~Scope() {
  if (p_.gpu_) {
    unsigned end = p_.takeQuery();
    glQueryCounter(end, GL_TIMESTAMP);
    p_.pending_.push_back({name_, queryBegin_, end});
    glPopDebugGroup();
  }
  p_.addCpu(name_,
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
}

void Profiler::addCpu(const std::string& name, double ms) {
  if (!calls_.count(name)) order_.push_back(name);
  cpuMs_[name] += ms;
  calls_[name] += 1;
}

void Profiler::resolve(bool wait) {
  if (wait && !pending_.empty()) glFinish();
  std::vector<Pending> still;
  for (auto& p : pending_) {
    GLint available = 0;
    glGetQueryObjectiv(p.end, GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available && !wait) {
      still.push_back(p);
      continue;
    }
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(p.begin, GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(p.end, GL_QUERY_RESULT, &t1);
    gpuMs_[p.name] += double(t1 - t0) * 1e-6;
    freeQueries_.push_back(p.begin);
    freeQueries_.push_back(p.end);
  }
  pending_.swap(still);
}

nlohmann::json Profiler::timingsMs() const {
  nlohmann::json j = nlohmann::json::object();
  for (auto& n : order_) j[n] = gpuMs_.count(n) ? gpuMs_.at(n) : cpuMs_.at(n);
  return j;
}

nlohmann::json Profiler::cpuTimingsMs() const {
  nlohmann::json j = nlohmann::json::object();
  for (auto& n : order_) j[n] = cpuMs_.at(n);
  return j;
}

nlohmann::json Profiler::callCounts() const {
  nlohmann::json j = nlohmann::json::object();
  for (auto& n : order_) j[n] = calls_.at(n);
  return j;
}

double Profiler::totalMs() const {
  double t = 0;
  const nlohmann::json all = timingsMs();  // items() must not outlive its object
  for (auto& [k, v] : all.items()) t += v.get<double>();
  return t;
}

}  // namespace vgi
