#pragma once
// Deformation fields (Goldenstein et al. 2005, section 3): resolution-independent deformations
// described over the continuous (u, v) domain, as a cascade of basic operations F_{u,v}(q) (eq 1)
// that any tessellation samples at its own vertices. A vector field V: (u, v) -> R^3 (section 3.2)
// is a function or a regular grid of samples, bilinearly interpolated (the geometry image of
// section 3.3, example 1); the stages are the constant field p = V(u, v) (eqs 2-3) and the
// AddVector field p = p_previous + q_k V(u, v) (eq 4).

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/parametric_surface.h"

namespace dnurbs {

/// A vector field V: (u, v) -> R^3 (Goldenstein et al. 2005, section 3.2).
using VectorField = std::function<Eigen::Vector3d(double u, double v)>;

/// A vector field given by samples on a regular grid of nodes over a ParameterDomain and
/// bilinearly interpolated between them: continuous, and exact for fields bilinear in (u, v).
///
/// Node (i, j) is at (domain.u_at(i / cells_u), domain.v_at(j / cells_v)) and is row
/// i * count_v + j of `samples` (count_u * count_v by 3), u outer. Along an open direction the
/// nodes include both ends (cells = count - 1, count >= 2); along a periodic one the last cell
/// wraps to the first node (cells = count, count >= 3). Outside an open direction's range the
/// field is clamped to its edge; a periodic direction wraps.
class SampledVectorField {
 public:
  /// Throws Error naming the value for counts below the minimum, a row count of `samples`
  /// other than count_u * count_v, or a non-finite sample.
  SampledVectorField(const ParameterDomain& domain, int count_u, int count_v,
                     Eigen::MatrixX3d samples);
  /// Samples `field` at the nodes (a geometry image of it).
  static SampledVectorField sample(const ParameterDomain& domain, int count_u, int count_v,
                                   const VectorField& field);

  const ParameterDomain& domain() const { return domain_; }
  int count_u() const { return count_u_; }
  int count_v() const { return count_v_; }
  const Eigen::MatrixX3d& samples() const { return samples_; }
  /// V(u, v), 3-vector.
  Eigen::Vector3d operator()(double u, double v) const;

 private:
  ParameterDomain domain_;
  int count_u_ = 0;
  int count_v_ = 0;
  Eigen::MatrixX3d samples_;
};

/// One stage of a deformation field cascade.
enum class DeformationKind {
  kConstant,   ///< p = V(u, v), ignoring the previous stage (Goldenstein et al. 2005, eqs. 2-3)
  kAddVector,  ///< p = p_previous + s V(u, v), s = q_k or 1 (Goldenstein et al. 2005, eq. 4)
};

/// A cascade of deformation fields over (u, v): F_{u,v}(q) of Goldenstein et al. 2005, eq. 1.
///
/// The cascade starts from an input point (the base surface's point, or zero) and applies its
/// stages in order. Every stage is affine in q, so p is affine in q and its parameter Jacobian
/// dp/dq is the sum of the vector fields of the AddVector stages after the last constant stage.
/// The result at (u, v) depends on (u, v) and q only, never on a mesh: two tessellations agree
/// exactly wherever they sample the same parameters.
class DeformationField {
 public:
  /// The empty cascade: p = input.
  DeformationField() = default;

  /// Appends p = V(u, v). Throws Error if `field` is empty.
  DeformationField& constant(VectorField field);
  /// Appends p += q_parameter V(u, v). Throws Error if `field` is empty or parameter < 0.
  DeformationField& add_vector(VectorField field, int parameter);
  /// Appends p += V(u, v) (a fixed offset, no parameter).
  DeformationField& add_vector(VectorField field);

  int stage_count() const { return static_cast<int>(stages_.size()); }
  DeformationKind stage_kind(int stage) const;
  /// One more than the largest parameter index used (the size q must have at least).
  int parameter_count() const { return parameter_count_; }

  /// p = F_{u,v}(q) applied to `input` (3-vector). Throws Error if q has fewer than
  /// parameter_count() entries.
  Eigen::Vector3d apply(const Eigen::VectorXd& q, double u, double v,
                        const Eigen::Vector3d& input = Eigen::Vector3d::Zero()) const;
  /// dp/dq at (u, v), 3 by parameter_count() (independent of q: every stage is affine).
  Eigen::Matrix3Xd parameter_jacobian(double u, double v) const;

 private:
  struct Stage {
    DeformationKind kind = DeformationKind::kConstant;
    VectorField field;
    int parameter = -1;  // -1: scale 1
  };
  std::vector<Stage> stages_;
  int parameter_count_ = 0;
};

/// The surface p(u, v) = field.apply(q, u, v, base.point(u, v)) over the base's domain and with
/// its orientation; normals by central differences of p (ParametricSurface without a normal
/// function). The field and q are copied. On a pole of the base domain the field must give one
/// value along the whole pole edge (a field of the base point, or a sampled field whose pole
/// row repeats one sample), or the deformed pole is no longer a point. Throws Error if q is
/// shorter than field.parameter_count().
ParametricSurface deformed_surface(const ParametricSurface& base, DeformationField field,
                                   Eigen::VectorXd q);

/// The surface p(u, v) = field.apply(q, u, v) of a cascade that starts with a constant field
/// (a geometry image or a PCA mean, Goldenstein et al. 2005, eqs. 2-4), over `domain`.
ParametricSurface deformation_field_surface(
    const ParameterDomain& domain, DeformationField field, Eigen::VectorXd q,
    NormalOrientation orientation = NormalOrientation::kSuCrossSv);

}  // namespace dnurbs
