#pragma once
// Material parameter functions over the parametric domain (Terzopoulos 2003, eqs. 1.25-1.26): mass
// density mu, damping density gamma and the stiffness weights (w1, w2 of curves; a10, a01, b20,
// b11, b02 of surfaces), each a constant or a function of the parameters.

#include <functional>
#include <string>

#include <Eigen/Core>

namespace dnurbs {

/// A scalar function of the material parameters u (curves use u.x() only), or a constant.
class MaterialFunction {
 public:
  /// The constant c everywhere (implicit, so that a double converts: `material.tension = 2.0`).
  MaterialFunction(double c = 0.0) : constant_(c) {}  // NOLINT(google-explicit-constructor)
  /// A function of u; it is evaluated once per quadrature point when matrices are built.
  MaterialFunction(std::function<double(const Eigen::Vector2d&)> function)  // NOLINT
      : function_(std::move(function)) {}

  double operator()(const Eigen::Vector2d& u) const { return function_ ? function_(u) : constant_; }
  bool is_constant() const { return !function_; }
  /// True if this is the constant 0 (so the term can be skipped).
  bool is_zero() const { return !function_ && constant_ == 0.0; }

  /// The value at u, checked: throws Error naming `name`, u and the value if it is not finite
  /// or (when non_negative) negative.
  double checked(const Eigen::Vector2d& u, const std::string& name, bool non_negative) const;

 private:
  double constant_ = 0.0;
  std::function<double(const Eigen::Vector2d&)> function_;
};

}  // namespace dnurbs
