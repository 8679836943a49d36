#pragma once
// A deformable model whose generalized coordinates are the parameters of a cascade of deformation
// fields (Goldenstein et al. 2005, section 3): x(u, v; q) = F_{u,v}(q) (eq 1), the cascade of
// constant fields (a geometry image or a mean shape, eqs. 2-3) and AddVector fields
// p += q_k V_k(u, v) (eq 4) over a base surface or from zero. Every stage is affine in q, so the
// Jacobian L(u, v) = dF_{u,v}/dq is the sum of the AddVector fields after the last constant stage,
// independent of q, and the matrices are constant:
//
//   M = integral mu L^T L du dv,   D = integral gamma L^T L du dv,   K = diag(k_0, ..., k_{P-1}),
//
// the integrals by tensor Gauss-Legendre points over a grid of (u, v) cells (the quadrature of
// every model's M), mu and gamma per unit (u, v) area as for D-NURBS (a distributed force is per
// unit parametric measure too, so gravity mu g gives integral L^T mu g du dv).
//
// The stiffness is a spring on each parameter toward q = 0, E = (1/2) sum_k k_k q_k^2: the
// parameters are the amplitudes of designed modes (the face's eyebrow, smile and jaw fields of
// section 3.4, the principal components of eq 4), q = 0 is the shape at rest (the geometry image
// or the mean of eq 3), and each mode's restoring force is its own, as the spring to the reference
// shape of a deformable superquadric's local deformations (Terzopoulos 2003, below eq 1.33). A
// membrane energy of the displacement would couple the parameters through the fields' overlap,
// which the paper's independent, hand-designed modes do not call for.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/surface/deformation_field.h"
#include "dnurbs/surface/parametric_surface.h"

namespace dnurbs {

/// Material, quadrature and tessellation of a DeformationFieldModel.
struct DeformationFieldSettings {
  double mass_density = 1.0;     ///< mu (> 0), per unit (u, v) area
  double damping_density = 0.0;  ///< gamma (>= 0), per unit (u, v) area
  /// k_k (>= 0) per parameter, parameter_count() entries; empty: every k_k = 0.
  Eigen::VectorXd stiffness;
  /// The quadrature grid: cells along u and v (>= 1) and Gauss-Legendre points per cell and
  /// direction (1..kMaxGaussPoints). 3 points integrate L^T L exactly for fields of degree <= 2
  /// per direction in a cell (a geometry image's bilinear cells when the grid matches its
  /// samples); smooth analytic fields converge with the cell count.
  int quadrature_cells_u = 8;
  int quadrature_cells_v = 8;
  int quadrature_points = 3;
  /// > 0: the model's tessellation (when the caller asks for none, ModelTessellationSettings::
  /// max_error = 0) is adaptive, refined by the surface error criterion to this max error
  /// (Goldenstein et al. 2005, section 5.2.3), at most `tessellation_max_level` bisections.
  double tessellation_max_error = 0.0;
  int tessellation_max_level = 16;
};

/// The deformation field cascade as a Model: q = (q_0, ..., q_{P-1}), P = field.parameter_count(),
/// coordinate k the parameter of the AddVector stages that name it.
class DeformationFieldModel : public Model {
 public:
  /// The cascade applied to base.point(u, v) over the base's domain and orientation (base given),
  /// or to zero over `domain` (no base: the cascade should start with a constant stage).
  /// `initial` has P entries. Throws Error naming the value for P = 0, a non-finite initial
  /// value, an `initial` or stiffness of the wrong size, a negative or non-finite stiffness,
  /// mu <= 0, gamma < 0, a quadrature setting out of range or a negative tessellation error.
  DeformationFieldModel(DeformationField field, std::optional<ParametricSurface> base,
                        const ParameterDomain& domain, Eigen::VectorXd initial,
                        DeformationFieldSettings settings);

  std::unique_ptr<Model> clone() const override;

  const DeformationField& field() const { return field_; }
  const DeformationFieldSettings& settings() const { return settings_; }

  int coordinate_count() const override { return field_.parameter_count(); }
  Eigen::VectorXd initial_coordinates() const override { return initial_; }
  int parametric_dimension() const override { return 2; }

  /// F_{u,v}(q) (Goldenstein et al. 2005, eq. 1).
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  /// L(u, v) = field.parameter_jacobian(u, v), 3 by P, the zero columns left out of the pattern.
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;

  bool matrices_are_constant() const override { return true; }
  const ModelMatrices* constant_matrices() const override { return &matrices_; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  /// integral L^T f du dv at the quadrature points; the sample's tangents are central
  /// differences of x (ParametricSurface::kDifferenceStep of the domain's extent) and its
  /// mass_density is mu.
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;

  /// S_u, S_v and J_u = dL/du, J_v = dL/dv (3 by P, every column listed) by central
  /// differences of x and L (one-sided at the domain's edges, ParametricSurface::kDifferenceStep
  /// of its extent); the bias terms are zero (L does not depend on q).
  void tangent_kinematics(ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u,
                          TangentKinematics& tangents) const override;

  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  NormalOrientation normal_orientation() const override;
  /// deformed_surface(base, field, q), or deformation_field_surface(domain, field, q).
  ParametricSurface parametric_surface(ConstVectorRef q) const override;
  /// The default tessellation (dynamics/core/model_tessellation.h), adaptive with the settings'
  /// tessellation_max_error when the caller's max_error is 0 and that is > 0.
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                          std::string name) const override;

 private:
  struct QuadraturePoint {
    Eigen::Vector2d parameter;
    double weight = 0.0;        ///< Gauss weight times the cell's du dv
    Eigen::Matrix3Xd jacobian;  ///< L at the point, 3 by P
  };
  Eigen::Vector3d input(double u, double v) const;
  // (u0, u1, v0, v1): the parameters of the difference tangents at u
  Eigen::Vector4d difference_parameters(const Eigen::Vector2d& u) const;

  DeformationField field_;
  std::optional<ParametricSurface> base_;
  ParameterDomain domain_;
  Eigen::VectorXd initial_;
  DeformationFieldSettings settings_;
  std::vector<QuadraturePoint> points_;
  ModelMatrices matrices_;
};

}  // namespace dnurbs
