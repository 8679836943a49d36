#include "dnurbs/dynamics/superquadric/deformable_superquadric_settings.h"

#include <cmath>
#include <initializer_list>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using Parameter = SuperquadricShapeParameter;

}  // namespace

// Parts -----------------------------------------------------------------------------------------

DeformableSuperquadricParts DeformableSuperquadricParts::rigid() {
  return {};
}

DeformableSuperquadricParts DeformableSuperquadricParts::global() {
  DeformableSuperquadricParts parts;
  // The superellipsoid's and the global deformation's indices are enumerators of two types:
  // the list is typed explicitly.
  for (const int k : std::initializer_list<int>{
           Parameter::kAspect1, Parameter::kAspect2, Parameter::kAspect3, Parameter::kSquareness1,
           Parameter::kSquareness2, Parameter::kTaper1, Parameter::kTaper2,
           Parameter::kBendAmplitude, Parameter::kTwist, Parameter::kShearX, Parameter::kShearY}) {
    parts.shape[static_cast<size_t>(k)] = true;
  }
  return parts;
}

DeformableSuperquadricParts DeformableSuperquadricParts::full() {
  DeformableSuperquadricParts parts = global();
  parts.local = true;
  return parts;
}

const char* superquadric_parameter_name(int k) {
  static const char* const names[kSuperquadricShapeParameterCount] = {
      "scale a",           "aspect a1", "aspect a2", "aspect a3",         "squareness e1",
      "squareness e2",     "taper t1",  "taper t2",  "bend amplitude b1", "bend offset b2",
      "bend frequency b3", "twist tau", "shear sx",  "shear sy"};
  if (k < 0 || k >= kSuperquadricShapeParameterCount) {
    throw make_error("superquadric shape parameter index ", k, " is outside 0..",
                     kSuperquadricShapeParameterCount - 1);
  }
  return names[k];
}

void validate_superquadric_settings(const DeformableSuperquadricSettings& s) {
  if (!(s.mass_density > 0.0) || !std::isfinite(s.mass_density)) {
    throw make_error("deformable superquadric mass density ", s.mass_density,
                     " must be positive and finite");
  }
  if (!(s.damping_alpha >= 0.0) || !std::isfinite(s.damping_alpha) || !(s.damping_beta >= 0.0) ||
      !std::isfinite(s.damping_beta)) {
    throw make_error("deformable superquadric Rayleigh damping alpha = ", s.damping_alpha,
                     ", beta = ", s.damping_beta, " must be non-negative and finite");
  }
  for (int k = 0; k < kSuperquadricShapeParameterCount; ++k) {
    if (!(s.shape_stiffness[k] >= 0.0) || !std::isfinite(s.shape_stiffness[k])) {
      throw make_error("deformable superquadric stiffness of ", superquadric_parameter_name(k),
                       " = ", s.shape_stiffness[k], " must be non-negative and finite");
    }
  }
  if (s.rest_shape) {
    for (int k = 0; k < kSuperquadricShapeParameterCount; ++k) {
      if (!std::isfinite((*s.rest_shape)[k])) {
        throw make_error("deformable superquadric rest shape entry ",
                         superquadric_parameter_name(k), " = ", (*s.rest_shape)[k],
                         " is not finite");
      }
    }
  }
  if (!(s.regularization >= 0.0) || !std::isfinite(s.regularization)) {
    throw make_error("deformable superquadric regularization ", s.regularization,
                     " must be non-negative and finite");
  }
}

}  // namespace dnurbs
