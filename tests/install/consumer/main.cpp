// Evaluates the rational circle through the installed headers and library, and links the CAD
// exchange of io/cad_file.h (dnurbs::cad and Open CASCADE when dnurbs was built with them);
// exits non-zero if the radius is off.
#include <cmath>
#include <cstdio>

#include "dnurbs/io/cad_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"

int main() {
  const dnurbs::NurbsCurve circle = dnurbs::full_circle(2.0);
  const double radius = circle.point(0.3).norm();
  std::printf("radius %.17g, CAD exchange %s\n", radius,
              dnurbs::cad_exchange_available() ? "on" : "off");
  return std::abs(radius - 2.0) < 1e-14 && dnurbs::cad_format_of("part.STEP") ? 0 : 1;
}
