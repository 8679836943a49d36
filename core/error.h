#pragma once
// The one exception type of dnurbs.

#include <charconv>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace dnurbs {

/// Thrown by library code for bad input (a decreasing knot vector, a weight <= 0, NaN, ...) and
/// for failures it cannot recover from. The message names the offending value.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

namespace detail {
/// Streams a message part; doubles in their shortest round-trip form (0.6, not 0.59999...).
template <typename Part>
void append_part(std::ostringstream& message, const Part& part) {
  if constexpr (std::is_floating_point_v<Part>) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), static_cast<double>(part));
    message.write(buffer, result.ptr - buffer);
  } else {
    message << part;
  }
}
}  // namespace detail

/// Builds a message from streamable parts: throw make_error("weight ", i, " is ", w).
template <typename... Parts>
Error make_error(const Parts&... parts) {
  std::ostringstream message;
  (detail::append_part(message, parts), ...);
  return Error(message.str());
}

}  // namespace dnurbs
