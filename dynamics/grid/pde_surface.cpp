#include "dnurbs/dynamics/grid/pde_surface.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/surface/grid_difference_operators.h"

namespace dnurbs {

namespace {

using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

void check_coefficient(double value, const char* name, bool positive) {
  if (!std::isfinite(value) || (positive ? !(value > 0.0) : !(value >= 0.0))) {
    throw make_error("PDE surface ", name, " = ", value, " is not ",
                     positive ? "positive" : "non-negative", " and finite");
  }
}

void check_material(const PdeSurfaceMaterial& material) {
  check_coefficient(material.b, "b", false);
  check_coefficient(material.c, "c", false);
  check_coefficient(material.d, "d", false);
  check_coefficient(material.mass_density, "density rho", true);
  check_coefficient(material.damping_density, "damping gamma", false);
  for (const auto& [name, value] :
       std::array<std::pair<const char*, double>, 4>{{{"tangent_u0 (su0)", material.tangent_u0},
                                                      {"tangent_u1 (su1)", material.tangent_u1},
                                                      {"tangent_v0 (sv0)", material.tangent_v0},
                                                      {"tangent_v1 (sv1)", material.tangent_v1}}}) {
    if (!std::isfinite(value)) {
      throw make_error("PDE surface boundary tangent ", name, " = ", value, " is not finite");
    }
  }
}

}  // namespace

PdeSurface::PdeSurface(const Grid& grid, const NodePositions& rest,
                       const PdeSurfaceMaterial& material,
                       const std::vector<DeformationRegion>& regions)
    : grid_(grid), material_(material), rest_(rest) {
  if (grid.nu() < 3 || grid.nv() < 3) {
    throw make_error("PDE surface grid of ", grid.nu(), " by ", grid.nv(),
                     " nodes is smaller than the 3 by 3 nodes it needs");
  }
  check_grid_positions(grid, rest, "rest position");
  check_material(material);
  choose_active_nodes(regions);
  build_unit_matrices();
  set_material(material);
}

void PdeSurface::choose_active_nodes(const std::vector<DeformationRegion>& regions) {
  // Deformation regions (Romero 2005, section 5) -> index boxes; active = strictly inside a box.
  const int nu = grid_.nu();
  const int nv = grid_.nv();
  const int n = grid_.node_count();
  std::vector<std::array<int, 4>> boxes;  // i_min, i_max, j_min, j_max
  if (regions.empty()) {
    boxes.push_back({0, nu - 1, 0, nv - 1});
  }
  for (const DeformationRegion& region : regions) {
    if (region.box) {
      if (region.box->isEmpty() || !region.box->min().allFinite() ||
          !region.box->max().allFinite()) {
        throw make_error("box region from (", region.box->min().x(), ", ", region.box->min().y(),
                         ", ", region.box->min().z(), ") to (", region.box->max().x(), ", ",
                         region.box->max().y(), ", ", region.box->max().z(),
                         ") is empty or not finite");
      }
    } else if (!(region.deformation_radius > 0.0) || !std::isfinite(region.deformation_radius) ||
               !region.centre.allFinite()) {
      throw make_error("deformation radius ", region.deformation_radius,
                       " is not positive and finite (or its centre is not finite)");
    }
    std::array<int, 4> box{nu, -1, nv, -1};
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d at = rest_.row(k).transpose();
      if (region.box ? region.box->contains(at)
                     : (at - region.centre).norm() < region.deformation_radius) {
        const auto [i, j] = grid_.node(k);
        box = {std::min(box[0], i), std::max(box[1], i), std::min(box[2], j), std::max(box[3], j)};
      }
    }
    if (box[1] - box[0] < 2 || box[3] - box[2] < 2) {
      if (region.box) {
        throw make_error("box region from (", region.box->min().x(), ", ", region.box->min().y(),
                         ", ", region.box->min().z(), ") to (", region.box->max().x(), ", ",
                         region.box->max().y(), ", ", region.box->max().z(),
                         ") spans fewer than the 3 by 3 nodes it needs");
      }
      throw make_error("deformation region of radius ", region.deformation_radius, " around (",
                       region.centre.x(), ", ", region.centre.y(), ", ", region.centre.z(),
                       ") spans fewer than the 3 by 3 nodes it needs");
    }
    boxes.push_back(box);
  }
  slot_.assign(static_cast<size_t>(n), -1);
  for (int k = 0; k < n; ++k) {
    const auto [i, j] = grid_.node(k);
    for (const auto& box : boxes) {
      if (i > box[0] && i < box[1] && j > box[2] && j < box[3]) {
        slot_[static_cast<size_t>(k)] = static_cast<int>(active_.size());
        active_.push_back(k);
        break;
      }
    }
  }
}

void PdeSurface::build_unit_matrices() {
  const int nu = grid_.nu();
  const int nv = grid_.nv();
  const int n = grid_.node_count();
  // Rest normals for the boundary tangents.
  const GridDifferenceOperators operators = grid_difference_operators(grid_);
  const NodePositions t1 = operators.t1 * rest_;
  const NodePositions t2 = operators.t2 * rest_;
  NodePositions normal(n, 3);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d cross = t1.row(k).transpose().cross(t2.row(k).transpose());
    const double length = cross.norm();
    normal.row(k) = length > 0.0 ? Eigen::RowVector3d((cross / length).transpose())
                                 : Eigen::RowVector3d::Zero();
  }

  // Romero 2005, eq. 8 by central differences, times the node area h^2, for b = c = d = 1.
  const double h = grid_.spacing();
  const double unit = h * h / (h * h * h * h);
  const int active_count = static_cast<int>(active_.size());
  std::array<std::vector<Eigen::Triplet<double>>, 3> triplets;  // b, c, d
  for (Eigen::VectorXd& tangent : unit_tangent_force_) {
    tangent = Eigen::VectorXd::Zero(3 * active_count);
  }
  const auto slot_at = [&](int i, int j) {
    return i < 0 || j < 0 || i >= nu || j >= nv ? -1
                                                : slot_[static_cast<size_t>(grid_.index(i, j))];
  };
  for (int a = 0; a < active_count; ++a) {
    const auto [i, j] = grid_.node(active_[static_cast<size_t>(a)]);
    // Fourth differences along u (b) and v (d): r(-2) - 4 r(-1) + 6 r(0) - 4 r(1) + r(2).
    for (const int axis : {0, 1}) {
      std::vector<Eigen::Triplet<double>>& fourth = triplets[axis == 0 ? 0 : 2];
      const int di = axis == 0 ? 1 : 0;
      const int dj = 1 - di;
      double diagonal = 6.0;
      for (const int side : {-1, 1}) {
        const int near = slot_at(i + side * di, j + side * dj);
        if (near >= 0) {
          fourth.emplace_back(a, near, -4.0 * unit);
          const int far = slot_at(i + 2 * side * di, j + 2 * side * dj);
          if (far >= 0) {
            fourth.emplace_back(a, far, unit);
          }
        } else {
          // Boundary node at rest; ghost beyond it r(2) = r(0) - 2 h s n0 (displacements).
          diagonal += 1.0;
          const int boundary = grid_.index(i + side * di, j + side * dj);
          unit_tangent_force_[static_cast<size_t>(2 * axis + (side < 0 ? 0 : 1))].segment<3>(
              3 * a) += unit * 2.0 * h * normal.row(boundary).transpose();
        }
      }
      fourth.emplace_back(a, a, diagonal * unit);
    }
    // Mixed difference (D_uu D_vv r): weights (1, -2, 1) (x) (1, -2, 1).
    const std::array<double, 3> w{1.0, -2.0, 1.0};
    for (int p = -1; p <= 1; ++p) {
      for (int r = -1; r <= 1; ++r) {
        const int other = slot_at(i + p, j + r);
        if (other >= 0) {
          triplets[1].emplace_back(
              a, other, unit * w[static_cast<size_t>(p + 1)] * w[static_cast<size_t>(r + 1)]);
        }
      }
    }
  }
  for (size_t k = 0; k < 3; ++k) {
    unit_stiffness_[k].resize(active_count, active_count);
    unit_stiffness_[k].setFromTriplets(triplets[k].begin(), triplets[k].end());
  }
  rest_coordinates_.resize(3 * active_count);
  for (int a = 0; a < active_count; ++a) {
    rest_coordinates_.segment<3>(3 * a) = rest_.row(active_[static_cast<size_t>(a)]).transpose();
  }
  initial_coordinates_ = rest_coordinates_;
}

void PdeSurface::set_material(const PdeSurfaceMaterial& material) {
  check_material(material);
  material_ = material;
  // K = b K_b + c K_c + d K_d and t = b (su0 t_u0 + su1 t_u1) + d (sv0 t_v0 + sv1 t_v1) from the
  // unit matrices and forces (header comment); a zero coefficient adds no entries
  const int active_count = static_cast<int>(active_.size());
  SparseMatrix scalar(active_count, active_count);
  for (const auto& [coefficient, unit] :
       std::array<std::pair<double, const SparseMatrix*>, 3>{{{material.b, &unit_stiffness_[0]},
                                                              {material.d, &unit_stiffness_[2]},
                                                              {material.c, &unit_stiffness_[1]}}}) {
    if (coefficient != 0.0) {
      scalar += coefficient * *unit;
    }
  }
  matrices_.stiffness = kronecker_identity(scalar, 3);
  tangent_force_ = material.b * (material.tangent_u0 * unit_tangent_force_[0] +
                                 material.tangent_u1 * unit_tangent_force_[1]) +
                   material.d * (material.tangent_v0 * unit_tangent_force_[2] +
                                 material.tangent_v1 * unit_tangent_force_[3]);
  const double area = grid_.spacing() * grid_.spacing();
  const int size = 3 * active_count;
  SparseMatrix identity(size, size);
  identity.setIdentity();
  matrices_.mass = (material.mass_density * area) * identity;
  matrices_.damping = material.damping_density > 0.0
                          ? SparseMatrix((material.damping_density * area) * identity)
                          : SparseMatrix(size, size);
}

Eigen::VectorXd PdeSurface::material_parameters() const {
  return pde_material_parameters(material_);
}

bool PdeSurface::set_material_parameters(ConstVectorRef values) {
  const PdeSurfaceMaterial material = pde_material_from_parameters(values);
  const PdeSurfaceMaterial& old = material_;
  const bool matrices = material.b != old.b || material.c != old.c || material.d != old.d ||
                        material.mass_density != old.mass_density ||
                        material.damping_density != old.damping_density;
  set_material(material);
  return matrices;
}

Eigen::VectorXd pde_material_parameters(const PdeSurfaceMaterial& material) {
  Eigen::VectorXd values(kPdeMaterialParameterCount);
  values << material.b, material.c, material.d, material.mass_density, material.damping_density,
      material.tangent_u0, material.tangent_u1, material.tangent_v0, material.tangent_v1;
  return values;
}

PdeSurfaceMaterial pde_material_from_parameters(ConstVectorRef values) {
  if (values.size() != kPdeMaterialParameterCount) {
    throw make_error("PDE surface material parameters have ", values.size(), " entries, not ",
                     kPdeMaterialParameterCount,
                     " (b, c, d, density, damping, su0, su1, sv0, sv1)");
  }
  PdeSurfaceMaterial material;
  material.b = values(0);
  material.c = values(1);
  material.d = values(2);
  material.mass_density = values(3);
  material.damping_density = values(4);
  material.tangent_u0 = values(5);
  material.tangent_u1 = values(6);
  material.tangent_v0 = values(7);
  material.tangent_v1 = values(8);
  return material;
}

void PdeSurface::set_plastic_flow(const std::optional<PlasticFlow>& flow) {
  if (flow) {
    check_plastic_flow(*flow);
  }
  plastic_flow_ = flow;
}

int PdeSurface::flow_rest_shape(ConstVectorRef q, double dt) {
  if (!plastic_flow_) {
    return 0;
  }
  if (q.size() != coordinate_count()) {
    throw make_error("PDE surface coordinates have ", q.size(), " entries, not ",
                     coordinate_count());
  }
  return flow_rest_positions(*plastic_flow_, dt, 3, q, rest_coordinates_);
}

Eigen::VectorXd PdeSurface::flowing_rest_coordinates() const {
  return plastic_flow_ ? rest_coordinates_ : Eigen::VectorXd();
}

void PdeSurface::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  if (!plastic_flow_) {
    Model::restore_flowing_rest_coordinates(rest);
  }
  check_rest_coordinates(rest, coordinate_count());
  rest_coordinates_ = rest;
}

NodePositions PdeSurface::positions(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("PDE surface coordinates have ", q.size(), " entries, not ",
                     coordinate_count());
  }
  NodePositions r = rest_;
  for (size_t a = 0; a < active_.size(); ++a) {
    r.row(active_[a]) = q.segment<3>(3 * static_cast<Eigen::Index>(a)).transpose();
  }
  return r;
}

std::vector<int> PdeSurface::nodes_within(const Eigen::Vector3d& centre, double radius) const {
  return dnurbs::nodes_within(initial_coordinates_, centre, radius);
}

std::vector<int> nodes_within(ConstVectorRef positions, const Eigen::Vector3d& centre,
                              double radius) {
  if (!(radius >= 0.0) || !std::isfinite(radius)) {
    throw make_error("force radius ", radius, " is not non-negative and finite");
  }
  if (!centre.allFinite()) {
    throw make_error("force region centre (", centre.x(), ", ", centre.y(), ", ", centre.z(),
                     ") is not finite");
  }
  std::vector<int> nodes;
  for (Eigen::Index a = 0; 3 * a < positions.size(); ++a) {
    if ((positions.segment<3>(3 * a) - centre).norm() <= radius) {
      nodes.push_back(static_cast<int>(a));
    }
  }
  return nodes;
}

Eigen::VectorXd PdeSurface::initial_coordinates() const {
  return initial_coordinates_;
}

Eigen::Vector3d PdeSurface::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (const auto& [node, weight] : grid_.bilinear_weights(u)) {
    if (weight == 0.0) {
      continue;
    }
    const int a = slot_[static_cast<size_t>(node)];
    x += weight * (a >= 0 ? Eigen::Vector3d(q.segment<3>(3 * a))
                          : Eigen::Vector3d(rest_.row(node).transpose()));
  }
  return x;
}

SparseMatrix PdeSurface::position_jacobian(ConstVectorRef /*q*/, const Eigen::Vector2d& u) const {
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& [node, weight] : grid_.bilinear_weights(u)) {
    const int a = slot_[static_cast<size_t>(node)];
    if (weight != 0.0 && a >= 0) {
      for (int c = 0; c < 3; ++c) {
        triplets.emplace_back(c, 3 * a + c, weight);
      }
    }
  }
  SparseMatrix jacobian(3, coordinate_count());
  jacobian.setFromTriplets(triplets.begin(), triplets.end());
  return jacobian;
}

void PdeSurface::assemble_matrices(ConstVectorRef /*q*/, ModelMatrices& matrices) const {
  matrices = matrices_;
}

void PdeSurface::add_internal_force(ConstVectorRef q, VectorRef force) const {
  force.noalias() -= matrices_.stiffness * (q - rest_coordinates_);
  force += tangent_force_;
}

double PdeSurface::potential_energy(ConstVectorRef q) const {
  const Eigen::VectorXd d = q - rest_coordinates_;
  return 0.5 * d.dot(matrices_.stiffness * d) - tangent_force_.dot(d);
}

void PdeSurface::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                       VectorRef force) const {
  const double area = grid_.spacing() * grid_.spacing();
  MaterialSample sample;
  sample.mass_density = material_.mass_density;
  const NodePositions r = positions(q);
  for (size_t a = 0; a < active_.size(); ++a) {
    const int k = active_[a];
    const auto [i, j] = grid_.node(k);
    sample.parameter = grid_.parameter(k);
    sample.position = r.row(k).transpose();
    sample.tangent_u = (r.row(grid_.index(i + 1, j)) - r.row(grid_.index(i - 1, j))).transpose() /
                       (2.0 * grid_.spacing());
    sample.tangent_v = (r.row(grid_.index(i, j + 1)) - r.row(grid_.index(i, j - 1))).transpose() /
                       (2.0 * grid_.spacing());
    force.segment<3>(3 * static_cast<Eigen::Index>(a)) += area * density(sample);
  }
}

int PdeSurface::control_point_offset(int i) const {
  if (i < 0 || i >= static_cast<int>(active_.size())) {
    throw make_error("active node slot ", i, " is outside 0..",
                     static_cast<int>(active_.size()) - 1);
  }
  return 3 * i;
}

int advance_frame(Integrator& integrator, System& system, double max_dt, double frame_rate) {
  if (!(max_dt > 0.0) || !std::isfinite(max_dt)) {
    throw make_error("sub-step max_dt = ", max_dt, " is not positive and finite");
  }
  if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) {
    throw make_error("frame rate ", frame_rate, " is not positive and finite");
  }
  const double frame = 1.0 / frame_rate;
  const int steps = std::max(1, static_cast<int>(std::ceil(frame / max_dt - 1e-9)));
  const double dt = frame / steps;
  for (int s = 0; s < steps; ++s) {
    integrator.step(system, dt);
  }
  return steps;
}

ParameterDomain PdeSurface::parameter_domain(ConstVectorRef /*q*/) const {
  return grid_parameter_domain(grid_);
}

TriangleMesh PdeSurface::tessellate(ConstVectorRef q, const ModelTessellationSettings& /*settings*/,
                                    std::string name) const {
  return grid_triangle_mesh(grid_, positions(q), std::move(name));
}

}  // namespace dnurbs
