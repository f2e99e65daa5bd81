// Errors for user input (exceptions naming the file/parameter and the value)
// and invariant checks (VGI_CHECK) for programming mistakes.
#pragma once
#include <sstream>
#include <stdexcept>
#include <string>

namespace vgi {

// Thrown for anything a user can fix: bad files, bad parameters, too-large grids.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& msg) : std::runtime_error(msg) {}
};

namespace detail {
inline void appendAll(std::ostringstream&) {}
template <typename T, typename... Rest>
void appendAll(std::ostringstream& os, const T& v, const Rest&... rest) {
  os << v;
  appendAll(os, rest...);
}
}  // namespace detail

// fail("scene '", path, "': bad value ", v) builds the message from its parts.
template <typename... Args>
[[noreturn]] void fail(const Args&... args) {
  std::ostringstream os;
  detail::appendAll(os, args...);
  throw Error(os.str());
}

}  // namespace vgi

#define VGI_CHECK(cond)                                                                             \
  do {                                                                                              \
    if (!(cond))                                                                                    \
      throw std::logic_error(std::string("internal check failed: " #cond " at ") + __FILE__ + ":" + \
                             std::to_string(__LINE__));                                             \
  } while (0)
