#pragma once
// The Model contract (DESIGN.md, "The Model contract"): what every dynamic model gives the
// integrators, forces and constraints. Seed 001 eq 1.24 in its general form
//
//   M(q) qdd + D(q) qd - f_int(q) = f + g(q, qd),      f_int(q) = -K q for linear models,
//
// with all vectors in velocity space (size velocity_count()). Models are stateless evaluators:
// the state (q, qd, t) lives in the System, and every evaluation takes the coordinates it is
// evaluated at, so integrators can evaluate trial states (Newton iterations) and roll back.

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace dnurbs {

/// Column-major sparse matrix used by every dynamics API.
using SparseMatrix = Eigen::SparseMatrix<double>;
/// A read-only view of a coordinate or velocity vector (a segment of the System's state).
using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;
/// A writable view of a velocity-space vector (a segment of a System-wide vector).
using VectorRef = Eigen::Ref<Eigen::VectorXd>;

/// The mass, damping and stiffness matrices of a model at one state, each
/// velocity_count() by velocity_count(), sparse and symmetric (both triangles stored).
/// A matrix with no non-zeros (damping of an undamped model) may be stored empty (0 by 0 is not
/// allowed: the size is always right, only the pattern may be empty).
struct ModelMatrices {
  SparseMatrix mass;       ///< M = integral mu L^T L
  SparseMatrix damping;    ///< D = integral gamma L^T L
  SparseMatrix stiffness;  ///< K, or the tangent stiffness -d f_int / dq for nonlinear models
};

/// Everything a distributed force density may depend on at one material point.
struct MaterialSample {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();  ///< u (curves use x only)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   ///< x(u)
  Eigen::Vector3d tangent_u = Eigen::Vector3d::Zero();  ///< dx/du
  Eigen::Vector3d tangent_v = Eigen::Vector3d::Zero();  ///< dx/dv (zero for curves)
  double mass_density = 0.0;                            ///< mu(u)
};

/// A force per unit parametric measure (du for curves, du dv for surfaces) at a material point:
/// gravity is mu g, pressure is p (x_u x x_v).
using ForceDensity = std::function<Eigen::Vector3d(const MaterialSample&)>;

/// The contract every dynamic model implements (D-NURBS curves and surfaces now; deformable
/// superquadrics, grid surfaces and snakes later). A model is a value: clone() copies it.
///
/// Sizes: q has coordinate_count() entries; velocities, forces and matrices live in velocity
/// space of velocity_count() entries. They differ for models whose coordinates are not a vector
/// space (a quaternion orientation has 4 coordinates and 3 angular velocities); such models
/// override advance_coordinates().
class Model {
 public:
  virtual ~Model() = default;
  virtual std::unique_ptr<Model> clone() const = 0;

  // Sizes and initial state -----------------------------------------------------------------
  virtual int coordinate_count() const = 0;
  virtual int velocity_count() const { return coordinate_count(); }
  /// The coordinates the model was built with (the System's initial state).
  virtual Eigen::VectorXd initial_coordinates() const = 0;
  /// 1 for curves, 2 for surfaces: how many entries of a material parameter are used.
  virtual int parametric_dimension() const = 0;

  // Kinematics ------------------------------------------------------------------------------
  /// x(u) at coordinates q.
  virtual Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const = 0;
  /// L(u) = dx/dq, 3 by velocity_count(), only the coordinates that influence x(u) non-zero.
  virtual SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const = 0;
  /// Ldot(u) qd = d^2 x / dt^2 - L qdd, the velocity-product part of a point's acceleration
  /// (zero where L does not depend on q). Constraint layers need it for their sigma term.
  virtual Eigen::Vector3d jacobian_rate_times_velocity(ConstVectorRef q, ConstVectorRef qd,
                                                       const Eigen::Vector2d& u) const;

  // Matrices and forces ---------------------------------------------------------------------
  /// True if M, D, K do not depend on q (then constant_matrices() is non-null and integrators
  /// factor once).
  virtual bool matrices_are_constant() const = 0;
  /// The constant matrices, or nullptr for state-dependent ones.
  virtual const ModelMatrices* constant_matrices() const { return nullptr; }
  /// M, D, K at q (for constant models a copy of constant_matrices()). Implementations reuse
  /// the storage of `matrices` where its pattern already fits.
  virtual void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const = 0;
  /// If M = S_M (x) I_b, D = S_D (x) I_b and K = S_K (x) I_b with the velocity coordinates
  /// grouped node by node (b per node), returns b and sets `scalar` to the scalar matrices
  /// (nodes by nodes); returns 0 otherwise. Only constant models may return non-zero. The
  /// integrators then factor one scalar matrix and solve b right-hand sides.
  virtual int kronecker_block_size() const { return 0; }
  virtual const ModelMatrices* scalar_matrices() const { return nullptr; }

  /// Adds the internal (elastic) force f_int(q) = -dE/dq to `force` (size velocity_count()).
  /// Default: -K(q) q, right for every model whose energy is (1/2) q^T K q.
  virtual void add_internal_force(ConstVectorRef q, VectorRef force) const;
  /// Elastic potential energy E(q) with f_int = -dE/dq. Default (1/2) q^T K(q) q.
  virtual double potential_energy(ConstVectorRef q) const;
  /// Adds the generalized inertial force g(q, qd) = -integral mu L^T Ldot qd (zero where M does
  /// not depend on q: the default adds nothing).
  virtual void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const;
  /// Adds L(u)^T f, the generalized force of a point force f at u.
  virtual void add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                               VectorRef force) const;
  /// Adds integral L^T f(u) over the parametric domain, f a force per unit parametric measure,
  /// by the model's quadrature rule.
  virtual void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                     VectorRef force) const = 0;

  // Coordinates -----------------------------------------------------------------------------
  /// q_out = q "+" dv, the coordinates reached by a velocity-space increment dv (size
  /// velocity_count()). Default: q + dv. Superquadrics advance their quaternion by the
  /// exponential map here.
  virtual void advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                                   Eigen::Ref<Eigen::VectorXd> q_out) const;
  /// Projects a state back onto the model's admissible set after a step (D-NURBS keeps free
  /// weights above their minimum). Default: nothing.
  virtual void project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const;

  /// Velocity-space index of the first coordinate of control point i (models with control
  /// points); throws Error otherwise.
  virtual int control_point_offset(int i) const;

  // Boundary conditions ---------------------------------------------------------------------
  /// Velocity-space indices held fixed (eliminated from every solve), sorted and unique.
  const std::vector<int>& fixed_coordinates() const { return fixed_coordinates_; }
  /// Fixes one velocity-space coordinate; throws Error naming the index if out of range.
  void fix_coordinate(int index);

 protected:
  Model() = default;
  Model(const Model&) = default;
  Model& operator=(const Model&) = default;
  Model(Model&&) = default;
  Model& operator=(Model&&) = default;

 private:
  std::vector<int> fixed_coordinates_;
};

}  // namespace dnurbs
