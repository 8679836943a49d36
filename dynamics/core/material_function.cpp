#include "dnurbs/dynamics/core/material_function.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

double MaterialFunction::checked(const Eigen::Vector2d& u, const std::string& name,
                                 bool non_negative) const {
  const double value = (*this)(u);
  if (!std::isfinite(value)) {
    throw make_error(name, " is ", value, " at u = (", u.x(), ", ", u.y(), ")");
  }
  if (non_negative && value < 0.0) {
    throw make_error(name, " is negative (", value, ") at u = (", u.x(), ", ", u.y(), ")");
  }
  return value;
}

}  // namespace dnurbs
