// Evaluates the rational circle through the installed headers and library; exits non-zero if
// the radius is off.
#include <cmath>
#include <cstdio>

#include "nurbs/primitive_shapes.h"

int main() {
  const dnurbs::NurbsCurve circle = dnurbs::full_circle(2.0);
  const double radius = circle.point(0.3).norm();
  std::printf("radius %.17g\n", radius);
  return std::abs(radius - 2.0) < 1e-14 ? 0 : 1;
}
