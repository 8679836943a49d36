#pragma once
// The Model contract (DESIGN.md, "The Model contract"): what every dynamic model gives the
// integrators, forces, constraints, optimizers, tessellation and scene files. Terzopoulos,
// "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations", eq. 1.24 in its
// general form
//
//   M(q) qdd + D(q) qd - f_int(q) = f + g(q, qd),      f_int(q) = -K q for linear models,
//
// with all vectors in velocity space (size velocity_count()). Models are stateless evaluators:
// the state (q, qd, t) lives in the System, and every evaluation takes the coordinates it is
// evaluated at, so integrators can evaluate trial states (Newton iterations) and roll back.
//
// No library code outside a model's own files names a concrete model type: everything a layer
// needs of a model is a virtual function here, with a default where a sensible one exists.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/core/sparse_matrix.h"
#include "dnurbs/dynamics/core/rigid_mass_properties.h"
#include "dnurbs/dynamics/core/sculpted_region.h"
#include "dnurbs/nurbs/shape.h"
#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

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

/// The parametric tangents S_u, S_v of a surface model at one material point and their
/// kinematics, for constraints on the surface's orientation (a held normal).
struct TangentKinematics {
  Eigen::Vector3d su = Eigen::Vector3d::Zero();       ///< S_u at q
  Eigen::Vector3d sv = Eigen::Vector3d::Zero();       ///< S_v at q
  Eigen::Vector3d su_rate = Eigen::Vector3d::Zero();  ///< J_u qd
  Eigen::Vector3d sv_rate = Eigen::Vector3d::Zero();  ///< J_v qd
  Eigen::Vector3d su_bias = Eigen::Vector3d::Zero();  ///< Jdot_u qd (zero where J_u is constant)
  Eigen::Vector3d sv_bias = Eigen::Vector3d::Zero();  ///< Jdot_v qd
  /// The velocity-space columns (ascending) where J_u = dS_u/dq or J_v is non-zero, and those
  /// columns of J_u and J_v (3 by #columns each).
  std::vector<int> columns;
  Eigen::Matrix3Xd ju;
  Eigen::Matrix3Xd jv;
};

/// A free rigid body's view of a model, for the rigid-body integrator: its coordinates are
/// [c (3) | unit quaternion (w, x, y, z) (4)] and its velocities [cdot (3) | body angular
/// velocity (3)], its mass properties constant and its damping mass-proportional.
struct RigidBodyProperties {
  RigidMassProperties mass;    ///< reference mass properties (body frame)
  double damping_alpha = 0.0;  ///< Rayleigh mass coefficient: D = alpha M
};

struct ModelTessellationSettings;

/// The contract every dynamic model implements. A model is a value: clone() copies it.
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
  /// S_u, S_v at u with their Jacobians, rates and velocity-product terms (surface models that
  /// support orientation constraints). Default: throws Error saying the model has none.
  virtual void tangent_kinematics(ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u,
                                  TangentKinematics& tangents) const;

  // Matrices and forces ---------------------------------------------------------------------
  /// True if M, D, K do not depend on q (then constant_matrices() is non-null and integrators
  /// factor once).
  virtual bool matrices_are_constant() const = 0;
  /// True if a linearly implicit step (IntegratorSettings::newton_iterations = 0) is not to be
  /// trusted with this model: its step matrix M + c_D D + c_K K leaves out terms of the same size
  /// as those it keeps (free-weight D-NURBS: d(M a)/dq, dg/dq and the curvature of the energy in
  /// the weights, which reparametrize the shape). Integrators then iterate Newton by default
  /// (IntegratorSettings::automatic_newton). Default: false.
  virtual bool needs_newton_iterations() const { return false; }
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
  /// Constant-matrix models whose internal force is f_int(q) = -K (q - q_r): the rest
  /// coordinates q_r (coordinate_count() entries; a D-NURBS rest shape), which the integrators
  /// subtract before they form K (q - q_r) from the scalar matrices instead of calling
  /// add_internal_force. A shape at its rest then feels exactly no force, and a small
  /// displacement is not the difference of two large products K q and K q_r. Null when q_r = 0
  /// (the default).
  virtual const Eigen::VectorXd* linear_rest_coordinates() const { return nullptr; }

  /// Adds the internal (elastic) force f_int(q) = -dE/dq to `force` (size velocity_count()).
  /// Default: -K(q) q, right for every model whose energy is (1/2) q^T K(q) q.
  virtual void add_internal_force(ConstVectorRef q, VectorRef force) const;
  /// Elastic potential energy E(q) with f_int = -dE/dq. Default (1/2) q^T K(q) q.
  virtual double potential_energy(ConstVectorRef q) const;
  /// Kinetic energy T(q, qd) = (1/2) qd^T M(q) qd (q of coordinate_count(), qd of
  /// velocity_count()). Default: one pass over the scalar mass matrix when M = S_M (x) I_b is
  /// constant, the constant M otherwise, else M assembled at q.
  virtual double kinetic_energy(ConstVectorRef q, ConstVectorRef qd) const;
  /// Adds the generalized inertial force g(q, qd) = -integral mu L^T Ldot qd (zero where M does
  /// not depend on q: the default adds nothing).
  virtual void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const;
  /// The model's terms of one integrator iterate in one evaluation: M, D, K at q into `matrices`
  /// (as assemble_matrices) and force += f_int(q), plus g(q, qd) when `inertial` (force and qd
  /// of velocity_count()). State-dependent models override it to share one pass over their
  /// quadrature points (free-weight D-NURBS: the rational Jacobian once per Gauss point).
  /// Default: assemble_matrices, add_internal_force and add_inertial_force in turn.
  virtual void assemble_step(ConstVectorRef q, ConstVectorRef qd, bool inertial,
                             ModelMatrices& matrices, VectorRef force) const;
  /// The right-hand side of one integrator iterate without the matrices: force += f_int(q)
  /// (+ g(q, qd) when `inertial`) - D(q) qd - M(q) a (a, qd, force of velocity_count()), for
  /// iterates that keep an earlier factorization (modified Newton). Models override it to skip
  /// the assembly (free-weight D-NURBS: one pass, O(#active control points) per Gauss point).
  /// Default: assemble_step, then the products with D and M.
  virtual void add_step_residual(ConstVectorRef q, ConstVectorRef qd, ConstVectorRef a,
                                 bool inertial, VectorRef force) const;
  /// Adds L(u)^T f, the generalized force of a point force f at u.
  virtual void add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                               VectorRef force) const;
  /// Adds integral L^T f(u) over the parametric domain, f a force per unit parametric measure,
  /// by the model's quadrature rule.
  virtual void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                     VectorRef force) const = 0;

  // What particular steppers and optimizers need ---------------------------------------------
  /// The node block size of the semi-implicit step (Terzopoulos' matrix from the current
  /// tensors, dynamics/integrators/semi_implicit_step.h): b when semi_implicit_matrices can
  /// give scalar (nodes by nodes) matrices with the coordinates grouped b per node, 0 otherwise.
  /// Default: kronecker_block_size().
  virtual int semi_implicit_block_size() const { return kronecker_block_size(); }
  /// The mass, damping and stiffness the semi-implicit step uses at q (f_int = -K q with K
  /// frozen at q): scalar ones (nodes by nodes) when `scalar`, else velocity-space ones.
  /// Default: scalar_matrices() when scalar, assemble_matrices(q) otherwise.
  virtual void semi_implicit_matrices(ConstVectorRef q, bool scalar, ModelMatrices& matrices) const;
  /// The coordinate index whose time derivative velocity v is, or -1 where velocity v has no
  /// such coordinate (a body angular velocity). Default: v when the counts are equal, else -1.
  virtual int velocity_coordinate(int velocity) const;
  /// Lower bounds of the coordinates for optimizers (velocity-space indices, -inf where
  /// unbounded, which `lower` holds on entry): D-NURBS free weights >= their minimum. Default:
  /// leaves `lower` as it is.
  virtual void coordinate_lower_bounds(VectorRef lower) const;
  /// The model's rigid-body view if it is a free rigid body (RigidBodyProperties), else
  /// nullopt (the default).
  virtual std::optional<RigidBodyProperties> rigid_body() const { return std::nullopt; }

  // Coordinates -----------------------------------------------------------------------------
  /// q_out = q "+" dv, the coordinates reached by a velocity-space increment dv (size
  /// velocity_count()). Default: q + dv. Superquadrics advance their quaternion by the
  /// exponential map here.
  virtual void advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                                   Eigen::Ref<Eigen::VectorXd> q_out) const;
  /// Projects a state back onto the model's admissible set after a step (D-NURBS keeps free
  /// weights above their minimum). Default: nothing.
  virtual void project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const;

  /// Velocity-space index of the first coordinate of control point (or node) i; throws Error
  /// for models without control points or nodes.
  virtual int control_point_offset(int i) const;

  // Shape -----------------------------------------------------------------------------------
  /// The parameter domain at q: (u, v) with its closures for surfaces, [u_min, u_max] (v
  /// unused) with periodic_u for closed curves. Default: throws Error.
  virtual ParameterDomain parameter_domain(ConstVectorRef q) const;
  /// Which tangent cross product the outward unit normal follows. Default: S_u x S_v.
  virtual NormalOrientation normal_orientation() const { return NormalOrientation::kSuCrossSv; }
  /// The surface at q (surface models): default x(u, v) = position(q, (u, v)) over
  /// parameter_domain(q) with difference normals and normal_orientation(); models with an exact
  /// form (NURBS) override it. The returned surface owns copies of the model and q.
  virtual ParametricSurface parametric_surface(ConstVectorRef q) const;
  /// The exact shape at q when the model is a NURBS curve or surface (shape files, export, CAD
  /// exchange); nullopt (the default) otherwise.
  virtual std::optional<Shape> exact_shape(ConstVectorRef q) const;
  /// A triangle mesh of the shape at q (the one tessellation path; the settings and the
  /// default are documented in dynamics/core/model_tessellation.h). Models whose shape is a mesh
  /// (grids) return it.
  virtual TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                                  std::string name) const;

  // Boundary conditions ---------------------------------------------------------------------
  /// Velocity-space indices held fixed (eliminated from every solve), sorted and unique.
  const std::vector<int>& fixed_coordinates() const { return fixed_coordinates_; }
  /// Fixes one velocity-space coordinate; throws Error naming the index if out of range.
  void fix_coordinate(int index);
  /// Fixes point i: a control point's position (D-NURBS; a free weight stays free) or a node's
  /// three coordinates (grids, snakes). Default: the three coordinates from
  /// control_point_offset(i); throws Error naming i if the model has no such point.
  virtual void fix_point(int i);
  /// Fixes every point on the border of an open surface. Default: throws Error (no border).
  virtual void fix_border();
  /// Local sculpting: fixes every point outside the support of `region` grown by `margin` rings
  /// and returns how many were frozen. Default: throws Error (not supported).
  virtual int freeze_outside(const SculptedRegion& region, int margin);

  // Keyable material (a run's schedules: Romero 2005, section 5.2.1.2) ------------------------
  /// The material parameters a run may change, in the model's own order (PdeSurface:
  /// pde_material_parameters); empty (the default) when the model's material is fixed.
  virtual Eigen::VectorXd material_parameters() const { return {}; }
  /// Sets them (the size of material_parameters(); Error naming the value, the model unchanged,
  /// when one is out of range) and rebuilds what depends on them; returns true if M, D or K
  /// changed (false when only forces did: the PDE surface's boundary tangents). A System's model
  /// changes through System::set_material_parameters, which tells the integrators. Default:
  /// throws Error (no keyable material).
  virtual bool set_material_parameters(ConstVectorRef values);

  // Plastic flow (dynamics/core/plastic_flow.h) -----------------------------------------------
  /// After a step of dt to q (coordinate_count()): moves the rest shape of a model whose rest
  /// shape yields and returns the number of nodes that yielded; 0 for other models (default).
  virtual int flow_rest_shape(ConstVectorRef q, double dt);
  /// The rest coordinates of a model whose rest shape yields (a checkpoint keeps them); empty
  /// for other models (the default).
  virtual Eigen::VectorXd flowing_rest_coordinates() const { return {}; }
  /// Sets them back (the size of flowing_rest_coordinates(), finite); throws Error naming the
  /// size otherwise.
  virtual void restore_flowing_rest_coordinates(ConstVectorRef rest);

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
