#pragma once
// The dynamic PDE surface (Romero 2005, eq. 8, after You et al.):
//
//   b d4r/du4 + c d4r/du2dv2 + d d4r/dv4 + rho d2r/dt2 + gamma dr/dt = f
//
// on a regular (u, v) grid with spacing h, applied to the displacement r - r0 from the rest mesh
// (so any rest mesh is at rest without force, Romero 2005, section 4.2), discretized with central
// differences (Romero 2005, section 4.3) and multiplied by the node area h^2, so M = rho h^2 I,
// D = gamma h^2 I, K = h^2 (b D_uuuu + c D_uuvv + d D_vvvv) and a point force acts on its node.
//
// Deformation regions (Romero 2005, section 5): around each force centre the nodes closer than the
// deformation radius (at rest), or the nodes inside an axis-aligned box (figure 12), define a
// (u, v) index box; nodes strictly inside a box are simulated, the box border is the boundary
// (held at rest) and everything outside is fixed and costs nothing: the model's coordinates are
// only the active nodes. Several regions make the union of their boxes; no region simulates the
// whole grid inside its border. Force regions and moving forces: dynamics/grid/pde_force_region.h.
//
// Boundary conditions at the region border: the boundary node stays at rest and the ghost node
// beyond it is r(-1) = r(1) - 2 h s n0 (central difference), so that the inward derivative of the
// displacement at the boundary is s n0, n0 the rest normal of the boundary node and s the
// boundary tangent tangent_u0 (boundary at smaller u), tangent_u1 (larger u), tangent_v0,
// tangent_v1. Non-zero tangents deform the surface without force (Romero 2005, figure 9); the
// internal force is affine, f_int = -K (q - r0) + t. M, D and K are constant, so the integrators
// factor once; the model does not claim the S (x) I_3 layout (kronecker_block_size() = 0) because
// the integrators' Kronecker path assumes f_int = -K q.
//
// Keyable material (Romero 2005, section 5.2.1.2: density, damping, b, c, d and the four boundary
// tangents are the tool's keyable attributes): set_material changes them between steps. K is
// linear in b, c, d, M in rho, D in gamma and t in b su0, b su1, d sv0, d sv1, so the constructor
// keeps the unit matrices K_b, K_c, K_d (b = c = d = 1) and unit tangent forces, and set_material
// only recombines them: no grid pass (a twentieth of a factorization of the step matrix on 51 x 51
// to 201 x 201 grids). In a running System change them through System::set_material_parameters
// (the Model contract's material_parameters, in the order of pde_material_parameters), which
// makes the integrators refactor when M, D or K changed (not for the tangents alone).
//
// Plastic behaviour (Romero 2005, section 1: the tool's surfaces are to behave as clay as well as
// elastically): with set_plastic_flow the rest positions r0 of the active nodes yield towards
// their positions by the rule of dynamics/core/plastic_flow.h after every committed step, so a
// push leaves a dent. The fixed nodes and the boundary normals keep the initial rest shape.

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/plastic_flow.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs {

/// Coefficients of Romero 2005, eq. 8 (uniform over the grid: the tool's isotropic materials;
/// PdeSurface::set_material changes them in time).
struct PdeSurfaceMaterial {
  double b = 1.0;             ///< d4/du4 coefficient (>= 0)
  double c = 2.0;             ///< d4/du2dv2 coefficient (>= 0; b = d = 1, c = 2 is the biharmonic)
  double d = 1.0;             ///< d4/dv4 coefficient (>= 0)
  double mass_density = 1.0;  ///< rho (> 0), mass rho h^2 per node
  double damping_density = 0.0;  ///< gamma (>= 0), damping gamma h^2 per node
  /// Boundary tangents (finite): the inward slope along the rest normal at the boundary at
  /// smaller u (tangent_u0), larger u (tangent_u1), smaller v and larger v (scene keys su0, su1,
  /// sv0, sv1 after the thesis).
  double tangent_u0 = 0.0;
  double tangent_u1 = 0.0;
  double tangent_v0 = 0.0;
  double tangent_v1 = 0.0;
};

/// A deformation region: the nodes within `deformation_radius` of `centre` at rest, or, for a box
/// region (Romero 2005, figure 12: "the squared deform region"), the nodes whose rest position lies
/// in the axis-aligned `box` (faces included; centre and radius are then unused).
struct DeformationRegion {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double deformation_radius = 1.0;
  std::optional<Eigen::AlignedBox3d> box = std::nullopt;
};

/// The PDE surface as a Model. Coordinates q = [r_a0, r_a1, ...], the positions of the active
/// nodes (active_nodes() lists their grid indices); the fixed nodes keep their rest positions.
class PdeSurface : public Model {
 public:
  /// Throws Error naming the value for a grid under 3 by 3 nodes, a non-finite rest position, a
  /// negative or non-finite coefficient, rho <= 0, a radius <= 0, a box that is empty or not
  /// finite, or a region without an interior node (Romero 2005: the region must be at least 3 by
  /// 3 nodes).
  PdeSurface(const Grid& grid, const NodePositions& rest, const PdeSurfaceMaterial& material = {},
             const std::vector<DeformationRegion>& regions = {});

  std::unique_ptr<Model> clone() const override { return std::make_unique<PdeSurface>(*this); }

  const Grid& grid() const { return grid_; }
  /// The initial rest shape of every grid node (#nodes by 3; plastic flow moves
  /// rest_coordinates(), not these).
  const NodePositions& rest_positions() const { return rest_; }
  /// The active nodes' rest positions r0 (3 per active node): the initial ones until plastic
  /// flow moves them.
  const Eigen::VectorXd& rest_coordinates() const { return rest_coordinates_; }
  /// Makes the rest positions of the active nodes yield by `flow` (checked) after every
  /// committed step (header comment), or stop yielding (nullopt; the rest stays where it is).
  void set_plastic_flow(const std::optional<PlasticFlow>& flow);
  const std::optional<PlasticFlow>& plastic_flow() const { return plastic_flow_; }
  /// Grid indices of the active nodes, ascending; active slot a holds node active_nodes()[a].
  const std::vector<int>& active_nodes() const { return active_; }
  /// The active slot of a grid node, or -1 for a fixed node.
  int active_slot(int node) const { return slot_[static_cast<size_t>(node)]; }
  /// Every grid node's position at q (#nodes by 3): active from q, fixed at rest.
  NodePositions positions(ConstVectorRef q) const;
  /// The active slots whose initial rest position is within `radius` of `centre` (the force region
  /// of Romero 2005): pass them to control_point_force (dynamics/core/forces.h).
  std::vector<int> nodes_within(const Eigen::Vector3d& centre, double radius) const;
  /// The constant force t of the boundary tangents (3 per active node).
  const Eigen::VectorXd& tangent_force() const { return tangent_force_; }
  const PdeSurfaceMaterial& material() const { return material_; }
  /// Changes the material (checked as the constructor does, Error naming the value; the model
  /// is unchanged then): M, D, K and t recombined from the unit matrices (header comment), the
  /// state and the rest shape untouched. A System holding a copy learns of it through
  /// System::set_material_parameters only.
  void set_material(const PdeSurfaceMaterial& material);
  /// pde_material_parameters(material()).
  Eigen::VectorXd material_parameters() const override;
  /// set_material(pde_material_from_parameters(values)); true unless only tangents changed.
  bool set_material_parameters(ConstVectorRef values) override;

  int coordinate_count() const override { return 3 * static_cast<int>(active_.size()); }
  Eigen::VectorXd initial_coordinates() const override;
  int parametric_dimension() const override { return 2; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  bool matrices_are_constant() const override { return true; }
  const ModelMatrices* constant_matrices() const override { return &matrices_; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  /// f_int = -K (q - r0) + t.
  void add_internal_force(ConstVectorRef q, VectorRef force) const override;
  /// E = (1/2) (q - r0)^T K (q - r0) - t . (q - r0).
  double potential_energy(ConstVectorRef q) const override;
  /// sum over active nodes of h^2 f(sample at the node).
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  /// Active slot i's coordinates start at 3 i.
  int control_point_offset(int i) const override;
  /// The whole grid's [0, (nu - 1) h] x [0, (nv - 1) h].
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// Every grid node at q (fixed ones at rest) as the node mesh; the segments are ignored.
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                          std::string name) const override;
  /// With plastic flow: the rule on every active node; returns the nodes that yielded.
  int flow_rest_shape(ConstVectorRef q, double dt) override;
  /// rest_coordinates() with plastic flow, empty without.
  Eigen::VectorXd flowing_rest_coordinates() const override;
  void restore_flowing_rest_coordinates(ConstVectorRef rest) override;

 private:
  // Construction steps: the active nodes of the deformation regions, then the unit stiffness
  // matrices and tangent forces (set_material combines them into K and t).
  void choose_active_nodes(const std::vector<DeformationRegion>& regions);
  void build_unit_matrices();

  Grid grid_;
  PdeSurfaceMaterial material_;
  NodePositions rest_;
  std::vector<int> active_;
  std::vector<int> slot_;
  Eigen::VectorXd initial_coordinates_;  ///< the active nodes at the initial rest shape
  Eigen::VectorXd rest_coordinates_;     ///< r0 of the active nodes (plastic flow moves them)
  std::optional<PlasticFlow> plastic_flow_;
  // Built once with the active nodes (they depend on the grid, the rest shape and the regions
  // only): K_b, K_c, K_d (active nodes by active nodes) of b = c = d = 1, and the tangent forces
  // of b = d = 1 and a unit tangent at u0, u1, v0, v1 (3 per active node).
  std::array<SparseMatrix, 3> unit_stiffness_;
  std::array<Eigen::VectorXd, 4> unit_tangent_force_;
  // Rebuilt by set_material: t and M, D, K.
  Eigen::VectorXd tangent_force_;
  ModelMatrices matrices_;
};

/// The number of PDE surface material parameters, and the material as the Model contract's
/// parameter vector [b, c, d, density rho, damping gamma, su0, su1, sv0, sv1] and back (Error
/// naming the size when it is not 9; the values are checked by set_material).
inline constexpr int kPdeMaterialParameterCount = 9;
Eigen::VectorXd pde_material_parameters(const PdeSurfaceMaterial& material);
PdeSurfaceMaterial pde_material_from_parameters(ConstVectorRef values);

/// The nodes whose positions (3 per node in `positions`, node a at 3 a) are within `radius` of
/// `centre`, ascending. Throws Error naming the radius if it is negative or not finite, or the
/// centre if it is not finite.
std::vector<int> nodes_within(ConstVectorRef positions, const Eigen::Vector3d& centre,
                              double radius);

/// Sub-steps to an output frame rate (Romero 2005, section 4.3: the solver runs until the frame's
/// 1/frame_rate has elapsed): ceil(1 / (frame_rate max_dt)) equal steps of at most max_dt.
/// Returns the number of steps. Throws Error naming max_dt or frame_rate if not positive.
int advance_frame(Integrator& integrator, System& system, double max_dt, double frame_rate = 24.0);

}  // namespace dnurbs
