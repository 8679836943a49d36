#pragma once
// One NURBS shape, a curve or a tensor-product surface: what shape files hold, what export and
// CAD exchange write, and the exact shape a model gives (Model::exact_shape).

#include <variant>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// A NURBS curve or a NURBS surface.
using Shape = std::variant<NurbsCurve, NurbsSurface>;

}  // namespace dnurbs
