#include "io/scene_simulation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include "constraints/point_constraints.h"
#include "constraints/surface_constraints.h"
#include "constraints/target_trajectory.h"
#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/dnurbs/dnurbs_curve.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "dynamics/core/forces.h"
#include "dynamics/dnurbs/local_sculpting.h"
#include "dynamics/grid/pde_surface.h"
#include "dynamics/grid/snake.h"
#include "dynamics/grid/terzopoulos_surface.h"
#include "io/scene_materials.h"
#include "surface/grid.h"
#include "surface/node_chain.h"
#include "surface/tessellation.h"

namespace dnurbs {
namespace {

std::string indexed(const char* list, size_t i) {
  std::string path = list;
  path += '[';
  path += std::to_string(i);
  path += ']';
  return path;
}

[[noreturn]] void fail(const Scene& scene, const std::string& path, const std::string& message) {
  std::string text = scene.source;
  text += ": ";
  text += path;
  text += ": ";
  text += message;
  throw Error(text);
}

// A schedule as a function of time (the spline is built once)
VectorOfTime vector_of_time(const VectorSchedule& schedule) {
  if (schedule.times.empty()) {
    const Eigen::Vector3d value = schedule.values.front();
    return [value](double) { return value; };
  }
  auto trajectory = std::make_shared<TargetTrajectory>(
      TargetTrajectory::keyframes(schedule.times, schedule.values));
  return [trajectory](double t) { return trajectory->position(t); };
}

ScalarOfTime scalar_of_time(const ScalarSchedule& schedule) {
  VectorSchedule vector;
  vector.times = schedule.times;
  for (double v : schedule.values) {
    vector.values.emplace_back(v, 0.0, 0.0);
  }
  VectorOfTime f = vector_of_time(vector);
  return [f](double t) { return f(t).x(); };
}

TargetTrajectory trajectory(const VectorSchedule& schedule) {
  if (schedule.times.empty()) {
    return TargetTrajectory::fixed(schedule.values.front());
  }
  return TargetTrajectory::keyframes(schedule.times, schedule.values);
}

// A force that acts while start <= t < end
Force windowed(Force force, double start, double end) {
  return [force = std::move(force), start, end](const Model& model, double time, ConstVectorRef q,
                                                ConstVectorRef qd, VectorRef f) {
    if (time >= start && time < end) {
      force(model, time, q, qd, f);
    }
  };
}

void fix_points(Model& model, const std::vector<int>& points) {
  if (auto* dnurbs = dynamic_cast<DNurbsModel*>(&model)) {
    for (int i : points) {
      if (i >= dnurbs->control_point_count()) {
        throw make_error("control point ", i, " does not exist (the model has ",
                         dnurbs->control_point_count(), ")");
      }
      dnurbs->fix_control_point(i);
    }
    return;
  }
  const int nodes = model.coordinate_count() / 3;
  for (int i : points) {
    if (i >= nodes) {
      throw make_error("node ", i, " does not exist (the model has ", nodes, ")");
    }
    const int offset = model.control_point_offset(i);
    for (int k = 0; k < 3; ++k) {
      model.fix_coordinate(offset + k);
    }
  }
}

std::unique_ptr<Model> build_model(const SceneModel& spec) {
  std::unique_ptr<Model> model;
  if (const auto* c = std::get_if<SceneDNurbsCurve>(&spec.spec)) {
    model = std::make_unique<DNurbsCurve>(
        c->curve,
        dnurbs_curve_material(c->mass_density, c->damping_density, c->tension, c->rigidity),
        dnurbs_settings(c->settings));
  } else if (const auto* s = std::get_if<SceneDNurbsSurface>(&spec.spec)) {
    const Eigen::Matrix<double, 5, 1> stiffness =
        (Eigen::Matrix<double, 5, 1>() << s->a10, s->a01, s->b20, s->b11, s->b02).finished();
    auto surface = std::make_unique<DNurbsSurface>(
        s->surface, dnurbs_surface_material(s->mass_density, s->damping_density, stiffness),
        dnurbs_settings(s->settings));
    if (spec.boundary.clamp_border) {
      surface->fix_border();
    }
    model = std::move(surface);
  } else if (const auto* sq = std::get_if<SceneSuperquadric>(&spec.spec)) {
    DeformableSuperquadricSettings settings;
    settings.parts = sq->parts == "rigid"    ? DeformableSuperquadricParts::rigid()
                     : sq->parts == "global" ? DeformableSuperquadricParts::global()
                                             : DeformableSuperquadricParts::full();
    settings.mass_density = sq->mass_density;
    settings.damping_alpha = sq->damping_alpha;
    settings.damping_beta = sq->damping_beta;
    settings.shape_stiffness = SuperquadricShapeParameters::Constant(sq->shape_stiffness);
    settings.local_stiffness = {sq->local_stiffness.x(), sq->local_stiffness.y(),
                                sq->local_stiffness.z()};
    settings.mesh_cells_u = sq->mesh_cells_u;
    settings.mesh_cells_v = sq->mesh_cells_v;
    settings.quadrature_points = sq->quadrature_points;
    settings.regularization = sq->regularization;
    const Eigen::Quaterniond orientation(sq->orientation(0), sq->orientation(1), sq->orientation(2),
                                         sq->orientation(3));
    model =
        std::make_unique<DeformableSuperquadricModel>(sq->shape, sq->centre, orientation, settings);
  } else if (const auto* t = std::get_if<SceneTerzopoulosSurface>(&spec.spec)) {
    const Grid grid(t->grid.nodes_u, t->grid.nodes_v, t->grid.spacing, 3);
    TerzopoulosMaterial material;
    material.mass_density = t->mass_density;
    material.damping_density = t->damping_density;
    material.eta = t->eta;
    material.xi = t->xi;
    TerzopoulosSettings settings;
    settings.normal =
        t->normal == "classic" ? NormalApproximation::kClassic : NormalApproximation::kChristoffel;
    settings.delta = t->delta;
    auto surface = std::make_unique<TerzopoulosSurface>(
        grid, flat_grid_positions(grid, t->grid.origin, t->grid.axis_u, t->grid.axis_v), material,
        settings);
    if (spec.boundary.clamp_border) {
      surface->clamp_border();
    }
    model = std::move(surface);
  } else if (const auto* p = std::get_if<ScenePdeSurface>(&spec.spec)) {
    const Grid grid(p->grid.nodes_u, p->grid.nodes_v, p->grid.spacing, 3);
    PdeSurfaceMaterial material;
    material.b = p->b;
    material.c = p->c;
    material.d = p->d;
    material.density = p->density;
    material.damping = p->damping;
    material.su0 = p->su0;
    material.su1 = p->su1;
    material.sv0 = p->sv0;
    material.sv1 = p->sv1;
    std::vector<DeformationRegion> regions;
    for (size_t r = 0; r < p->region_centres.size(); ++r) {
      regions.push_back({p->region_centres[r], p->region_radii[r]});
    }
    model = std::make_unique<PdeSurface>(
        grid, flat_grid_positions(grid, p->grid.origin, p->grid.axis_u, p->grid.axis_v), material,
        regions);
  } else {
    const auto& snake = std::get<SceneSnake>(spec.spec);
    const NodeChain chain(static_cast<int>(snake.nodes.size()), snake.closed);
    NodePositions nodes(static_cast<Eigen::Index>(snake.nodes.size()), 3);
    for (size_t i = 0; i < snake.nodes.size(); ++i) {
      nodes.row(static_cast<Eigen::Index>(i)) = snake.nodes[i].transpose();
    }
    SnakeMaterial material;
    material.mass_density = snake.mass_density;
    material.damping_density = snake.damping_density;
    material.constant_tension = snake.tension;
    material.constant_rigidity = snake.rigidity;
    model = std::make_unique<Snake>(chain, nodes, material);
  }
  fix_points(*model, spec.boundary.fixed_points);
  return model;
}

// 1 % of the diagonal of a point set's bounding box (tube radius of curve meshes)
double tube_radius(const Eigen::MatrixX3d& points) {
  const double diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  return diagonal > 0.0 ? 0.01 * diagonal : 0.01;
}

int segments(int resolution, double scale, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(scale * resolution)));
}

// A (u, v) lattice of model points: nu by nv samples, v periodic (no repeated seam) if asked
TriangleMesh sampled_mesh(const Model& model, ConstVectorRef q, double u0, double u1, double v0,
                          double v1, int cells_u, int cells_v, bool periodic_v,
                          const std::string& name) {
  const int nu = cells_u + 1;
  const int nv = periodic_v ? cells_v : cells_v + 1;
  TriangleMesh mesh;
  mesh.name = name;
  mesh.vertices.resize(nu * nv, 3);
  mesh.uv.resize(nu * nv, 2);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector2d u(u0 + (u1 - u0) * i / cells_u, v0 + (v1 - v0) * j / cells_v);
      mesh.vertices.row(i * nv + j) = model.position(q, u).transpose();
      mesh.uv.row(i * nv + j) = u.transpose();
    }
  }
  mesh.triangles.resize(2 * cells_u * cells_v, 3);
  int t = 0;
  for (int i = 0; i < cells_u; ++i) {
    for (int j = 0; j < cells_v; ++j) {
      const int a = i * nv + j;
      const int b = (i + 1) * nv + j;
      const int c = (i + 1) * nv + (j + 1) % nv;
      const int d = i * nv + (j + 1) % nv;
      mesh.triangles.row(t++) << a, b, c;
      mesh.triangles.row(t++) << a, c, d;
    }
  }
  return mesh;
}

// A polyline of nodes as a degree-1 NURBS curve (for the tube mesh of a snake)
NurbsCurve polyline(const NodePositions& nodes, bool closed) {
  const int n = static_cast<int>(nodes.rows());
  std::vector<double> knots;
  if (closed) {
    for (int i = 0; i <= n; ++i) {
      knots.push_back(static_cast<double>(i) / n);
    }
    return NurbsCurve(KnotVector::periodic(1, knots), nodes);
  }
  knots.push_back(0.0);
  for (int i = 0; i < n; ++i) {
    knots.push_back(static_cast<double>(i) / (n - 1));
  }
  knots.push_back(1.0);
  return NurbsCurve(KnotVector(1, knots), nodes);
}

// Local sculpting of model `index` (boundary.local_sculpting_margin >= 0): the parameters and
// control points its forces and constraints act on; gravity, pressure and curve-on-surface
// constraints act everywhere, and then nothing is frozen.
void freeze_outside_scene_region(const Scene& scene, int index, Model& model) {
  SculptedRegion region;
  bool everywhere = false;
  for (const SceneForce& force : scene.forces) {
    if (const auto* p = std::get_if<ScenePointForce>(&force.spec); p && p->model == index) {
      region.parameters.push_back(p->at);
    } else if (const auto* s = std::get_if<SceneSpringForce>(&force.spec); s && s->model == index) {
      region.parameters.push_back(s->at);
    } else if (const auto* c = std::get_if<SceneControlPointForce>(&force.spec);
               c && c->model == index) {
      region.control_points.insert(region.control_points.end(), c->control_points.begin(),
                                   c->control_points.end());
    } else if (const auto* g = std::get_if<SceneGravity>(&force.spec)) {
      everywhere = everywhere || g->model == -1 || g->model == index;
    } else if (const auto* pressure = std::get_if<ScenePressure>(&force.spec)) {
      everywhere = everywhere || pressure->model == index;
    }
  }
  for (const SceneConstraint& constraint : scene.constraints) {
    if (const auto* t = std::get_if<ScenePointTargetConstraint>(&constraint.spec);
        t && t->model == index) {
      region.parameters.push_back(t->at);
    } else if (const auto* pp = std::get_if<ScenePointToPointConstraint>(&constraint.spec)) {
      if (pp->model_a == index) {
        region.parameters.push_back(pp->at_a);
      }
      if (pp->model_b == index) {
        region.parameters.push_back(pp->at_b);
      }
    } else if (const auto* h = std::get_if<SceneHingeConstraint>(&constraint.spec)) {
      if (h->model_a == index) {
        region.parameters.insert(region.parameters.end(), {h->axis_a0, h->axis_a1});
      }
      if (h->model_b == index) {
        region.parameters.insert(region.parameters.end(), {h->axis_b0, h->axis_b1});
      }
    } else if (const auto* c = std::get_if<SceneControlPointConstraint>(&constraint.spec);
               c && c->model == index) {
      region.control_points.push_back(c->control_point);
    } else if (const auto* n = std::get_if<SceneSurfaceNormalConstraint>(&constraint.spec);
               n && n->model == index) {
      region.parameters.push_back(n->at);
    } else if (const auto* cs = std::get_if<SceneCurveOnSurfaceConstraint>(&constraint.spec)) {
      everywhere = everywhere || cs->curve_model == index || cs->surface_model == index;
    }
  }
  if (everywhere) {
    return;
  }
  const int margin = scene.models[static_cast<size_t>(index)].boundary.local_sculpting_margin;
  if (auto* surface = dynamic_cast<DNurbsSurface*>(&model)) {
    freeze_outside_sculpted_region(*surface, region, margin);
  } else if (auto* curve = dynamic_cast<DNurbsCurve*>(&model)) {
    freeze_outside_sculpted_region(*curve, region, margin);
  }
}

// Sizes of a symmetric pattern and of its LDL^T factor, and the work of one factorisation.
struct FactorSize {
  long long matrix_non_zeros = 0;
  long long factor_non_zeros = 0;   // -1 if the pattern could not be factored
  double factorization_work = 0.0;  // sum over columns of (entries of L in the column)^2
};

FactorSize factor_size(const SparseMatrix& matrix) {
  // Values that make the pattern positive definite: the factor's pattern is what counts
  SparseMatrix a = matrix;
  Eigen::VectorXd row_count = Eigen::VectorXd::Zero(a.rows());
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      it.valueRef() = it.row() == it.col() ? 0.0 : -1.0;
      row_count(it.row()) += 1.0;
    }
  }
  SparseMatrix diagonal(a.rows(), a.cols());
  diagonal.setIdentity();
  for (int i = 0; i < a.rows(); ++i) {
    diagonal.coeffRef(i, i) = row_count(i) + 1.0;
  }
  a += diagonal;
  FactorSize size;
  size.matrix_non_zeros = matrix.nonZeros();
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);  // AMD ordering, as the integrators use
  if (ldlt.info() != Eigen::Success) {
    size.factor_non_zeros = -1;
    return size;
  }
  const auto& factor = ldlt.matrixL().nestedExpression();
  size.factor_non_zeros = factor.nonZeros();
  for (int k = 0; k < factor.outerSize(); ++k) {
    const double column =
        static_cast<double>(factor.outerIndexPtr()[k + 1] - factor.outerIndexPtr()[k]);
    size.factorization_work += column * column;
  }
  return size;
}

// The rows and columns of `matrix` whose index is not in `fixed` (sorted): the system the
// integrators solve once the fixed coordinates are eliminated
SparseMatrix free_block(const SparseMatrix& matrix, const std::vector<int>& fixed) {
  std::vector<int> position(static_cast<size_t>(matrix.rows()), -1);
  int free_count = 0;
  for (int i = 0; i < matrix.rows(); ++i) {
    if (!std::binary_search(fixed.begin(), fixed.end(), i)) {
      position[static_cast<size_t>(i)] = free_count++;
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < matrix.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      const int row = position[static_cast<size_t>(it.row())];
      const int column = position[static_cast<size_t>(it.col())];
      if (row >= 0 && column >= 0) {
        entries.emplace_back(row, column, it.value());
      }
    }
  }
  SparseMatrix block(free_count, free_count);
  block.setFromTriplets(entries.begin(), entries.end());
  return block;
}

// Sizes and the work of one solve of a model at its initial state, fixed coordinates eliminated
SceneModelCost model_cost(const Model& model) {
  SceneModelCost c;
  c.coordinates = model.coordinate_count();
  c.velocities = model.velocity_count();
  std::vector<int> fixed = model.fixed_coordinates();
  std::sort(fixed.begin(), fixed.end());
  c.fixed = static_cast<int>(fixed.size());
  c.constant_matrices = model.matrices_are_constant();
  c.kronecker_block = model.kronecker_block_size();
  ModelMatrices matrices;
  if (c.kronecker_block > 0 && model.scalar_matrices() != nullptr) {
    matrices = *model.scalar_matrices();
    // A scalar node is eliminated when all of its x, y, z are fixed
    std::vector<int> fixed_nodes;
    for (size_t k = 0; k + 2 < fixed.size(); ++k) {
      if (fixed[k] % 3 == 0 && fixed[k + 1] == fixed[k] + 1 && fixed[k + 2] == fixed[k] + 2) {
        fixed_nodes.push_back(fixed[k] / 3);
      }
    }
    fixed = fixed_nodes;
  } else {
    model.assemble_matrices(model.initial_coordinates(), matrices);
  }
  SparseMatrix sum = matrices.mass;
  if (matrices.damping.nonZeros() > 0) {
    sum += matrices.damping;
  }
  if (matrices.stiffness.nonZeros() > 0) {
    sum += matrices.stiffness;
  }
  // The christoffel Terzopoulos stiffness is not symmetric: factor its symmetric pattern
  const SparseMatrix transposed = sum.transpose();
  sum += transposed;
  const FactorSize size = factor_size(free_block(sum, fixed));
  c.matrix_non_zeros = size.matrix_non_zeros;
  c.factor_non_zeros = size.factor_non_zeros;
  // One solve: a forward and a backward substitution per right-hand side with a constant
  // factor; a factorisation first when the matrices change with the state
  const int right_hand_sides = c.kronecker_block > 0 ? c.kronecker_block : 1;
  c.solve_work = 2.0 * static_cast<double>(size.factor_non_zeros) * right_hand_sides +
                 (c.constant_matrices ? 0.0 : size.factorization_work);
  return c;
}

// The path a scene would pay for without the library's automatic choice for this model, and
// what that choice is; nullopt when the model already takes the naive path
std::optional<std::pair<SceneModel, std::string>> naive_variant(const SceneModel& spec) {
  SceneModel naive = spec;
  if (auto* c = std::get_if<SceneDNurbsCurve>(&naive.spec); c && !c->settings.free_weights) {
    c->settings.free_weights = true;
    return std::pair{naive, std::string("fixed weights (naive: free weights)")};
  }
  if (auto* s = std::get_if<SceneDNurbsSurface>(&naive.spec); s && !s->settings.free_weights) {
    s->settings.free_weights = true;
    return std::pair{naive, std::string("fixed weights (naive: free weights)")};
  }
  if (auto* sq = std::get_if<SceneSuperquadric>(&naive.spec); sq && sq->parts != "full") {
    const std::string choice = sq->parts + " parts only (naive: rigid, global and local parts)";
    sq->parts = "full";
    return std::pair{naive, choice};
  }
  if (auto* p = std::get_if<ScenePdeSurface>(&naive.spec); p && !p->region_centres.empty()) {
    p->region_centres.clear();
    p->region_radii.clear();
    return std::pair{naive, std::string("deformation regions (naive: every grid node)")};
  }
  return std::nullopt;
}

}  // namespace

SceneSimulation::SceneSimulation(Scene scene) : scene_(std::move(scene)) {
  // Models and boundary conditions
  for (size_t i = 0; i < scene_.models.size(); ++i) {
    const SceneModel& spec = scene_.models[i];
    std::unique_ptr<Model> model;
    try {
      model = build_model(spec);
    } catch (const Error& error) {
      fail(scene_, indexed("models", i), error.what());
    }
    if (spec.boundary.local_sculpting_margin >= 0) {
      try {
        freeze_outside_scene_region(scene_, static_cast<int>(i), *model);
      } catch (const Error& error) {
        fail(scene_, indexed("models", i) + ".boundary.local_sculpting_margin", error.what());
      }
    }
    system_.add_model(*model);
    if (const auto* c = std::get_if<SceneDNurbsCurve>(&spec.spec)) {
      tube_radii_.push_back(tube_radius(c->curve.control_points()));
    } else if (const auto* s = std::get_if<SceneSnake>(&spec.spec)) {
      Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(s->nodes.size()), 3);
      for (size_t k = 0; k < s->nodes.size(); ++k) {
        nodes.row(static_cast<Eigen::Index>(k)) = s->nodes[k].transpose();
      }
      tube_radii_.push_back(tube_radius(nodes));
    } else {
      tube_radii_.push_back(0.0);
    }
  }
  // Forces
  for (size_t i = 0; i < scene_.forces.size(); ++i) {
    const SceneForce& force = scene_.forces[i];
    const std::string path = indexed("forces", i);
    try {
      if (const auto* p = std::get_if<ScenePointForce>(&force.spec)) {
        system_.add_force(p->model, windowed(point_force(p->at, vector_of_time(p->force)),
                                             force.start, force.end));
      } else if (const auto* s = std::get_if<SceneSpringForce>(&force.spec)) {
        system_.add_force(s->model,
                          windowed(spring_force(s->at, vector_of_time(s->target), s->stiffness),
                                   force.start, force.end));
      } else if (const auto* c = std::get_if<SceneControlPointForce>(&force.spec)) {
        const Model& model = system_.model(c->model);
        for (size_t k = 0; k < c->control_points.size(); ++k) {
          const int index = c->control_points[k];
          try {
            const int offset = model.control_point_offset(index);
            if (offset + 3 > model.velocity_count()) {
              throw make_error("control point ", index, " does not exist");
            }
          } catch (const Error& error) {
            fail(scene_, path + ".control_points[" + std::to_string(k) + "]", error.what());
          }
        }
        system_.add_force(c->model,
                          windowed(control_point_force(c->control_points, vector_of_time(c->force)),
                                   force.start, force.end));
      } else if (const auto* g = std::get_if<SceneGravity>(&force.spec)) {
        for (int m = 0; m < system_.model_count(); ++m) {
          if (g->model < 0 || g->model == m) {
            system_.add_force(m, windowed(gravity(g->acceleration), force.start, force.end));
          }
        }
      } else {
        const auto& p = std::get<ScenePressure>(force.spec);
        system_.add_force(p.model,
                          windowed(pressure(scalar_of_time(p.pressure)), force.start, force.end));
      }
    } catch (const Error& error) {
      const std::string message = error.what();
      if (message.starts_with(scene_.source + ": ")) {
        throw;
      }
      fail(scene_, path, message);
    }
  }
  // Constraints
  for (size_t i = 0; i < scene_.constraints.size(); ++i) {
    const SceneConstraint& c = scene_.constraints[i];
    BaumgarteParameters parameters;
    parameters.alpha = c.alpha;
    parameters.beta = c.beta;
    try {
      if (const auto* t = std::get_if<ScenePointTargetConstraint>(&c.spec)) {
        solver_.add(system_, PointTargetConstraint(t->model, t->at, trajectory(t->target)),
                    parameters);
      } else if (const auto* p = std::get_if<ScenePointToPointConstraint>(&c.spec)) {
        solver_.add(system_, PointToPointConstraint(p->model_a, p->at_a, p->model_b, p->at_b),
                    parameters);
      } else if (const auto* h = std::get_if<SceneHingeConstraint>(&c.spec)) {
        solver_.add(
            system_,
            HingeConstraint(h->model_a, h->axis_a0, h->axis_a1, h->model_b, h->axis_b0, h->axis_b1),
            parameters);
      } else if (const auto* cp = std::get_if<SceneControlPointConstraint>(&c.spec)) {
        solver_.add(system_, ControlPointConstraint(cp->model, cp->control_point, cp->target),
                    parameters);
      } else if (const auto* n = std::get_if<SceneSurfaceNormalConstraint>(&c.spec)) {
        solver_.add(system_, SurfaceNormalConstraint(n->model, n->at, n->direction), parameters);
      } else {
        const auto& cos = std::get<SceneCurveOnSurfaceConstraint>(c.spec);
        for (auto& constraint : curve_on_surface_constraints(system_, cos.curve_model,
                                                             cos.surface_model, cos.samples)) {
          solver_.add(system_, std::move(constraint), parameters);
        }
      }
    } catch (const Error& error) {
      fail(scene_, indexed("constraints", i), error.what());
    }
  }
  // Probes: the model must be able to place the point
  for (size_t i = 0; i < scene_.probes.size(); ++i) {
    try {
      const Eigen::Vector3d x = system_.position(scene_.probes[i].model, scene_.probes[i].at);
      if (!x.allFinite()) {
        throw make_error("the probe's position is not finite");
      }
    } catch (const Error& error) {
      fail(scene_, indexed("probes", i), error.what());
    }
  }
  // Integrator
  IntegratorSettings settings;
  settings.scheme = parse_integrator_scheme(scene_.integrator.scheme);
  settings.newmark_beta = scene_.integrator.newmark_beta;
  settings.newmark_gamma = scene_.integrator.newmark_gamma;
  settings.newton_iterations = scene_.integrator.newton_iterations;
  settings.newton_tolerance = scene_.integrator.newton_tolerance;
  integrator_ = Integrator(settings);
  hash_ = scene_state_hash(scene_);
}

void SceneSimulation::step() {
  const Eigen::VectorXd q = system_.coordinates();
  const Eigen::VectorXd qd = system_.velocities();
  const bool valid = system_.accelerations_valid();
  const Eigen::VectorXd a = valid ? system_.accelerations() : Eigen::VectorXd();
  const double time = system_.time();
  auto restore_last = [&]() {
    system_.set_state(q, qd, time);
    if (valid) {
      system_.set_accelerations(a);
    }
  };
  const double dt = scene_.integrator.dt;
  try {
    if (solver_.constraint_count() > 0) {
      solver_.step(integrator_, system_, dt);
    } else {
      integrator_.step(system_, dt);
    }
  } catch (const Error& error) {
    restore_last();
    throw SimulationDiverged(
        make_error("step ", steps_ + 1, " (t = ", time + dt, ") diverged: ", error.what()).what());
  }
  const double energy = system_.kinetic_energy() + system_.potential_energy();
  if (!std::isfinite(energy) || energy > scene_.integrator.max_energy) {
    restore_last();
    throw SimulationDiverged(
        make_error("step ", steps_ + 1, " (t = ", time + dt, ") diverged: the energy ", energy,
                   " exceeds integrator.max_energy = ", scene_.integrator.max_energy)
            .what());
  }
  ++steps_;
}

SceneSample SceneSimulation::sample() const {
  SceneSample s;
  s.step = steps_;
  s.time = system_.time();
  s.kinetic_energy = system_.kinetic_energy();
  s.potential_energy = system_.potential_energy();
  s.violations = solver_.violations(system_);
  for (const auto& probe : scene_.probes) {
    s.probes.push_back(system_.position(probe.model, probe.at));
  }
  return s;
}

std::vector<std::string> SceneSimulation::log_columns() const {
  std::vector<std::string> columns = {"time", "kinetic_energy", "potential_energy", "total_energy",
                                      "max_violation"};
  for (int i = 0; i < solver_.constraint_count(); ++i) {
    columns.push_back("violation_" + std::to_string(i));
  }
  for (const auto& probe : scene_.probes) {
    for (const char* axis : {"_x", "_y", "_z"}) {
      columns.push_back(probe.name + axis);
    }
  }
  return columns;
}

std::vector<double> SceneSimulation::log_row(const SceneSample& s) const {
  std::vector<double> row = {s.time, s.kinetic_energy, s.potential_energy,
                             s.kinetic_energy + s.potential_energy,
                             s.violations.size() > 0 ? s.violations.maxCoeff() : 0.0};
  for (Eigen::Index i = 0; i < s.violations.size(); ++i) {
    row.push_back(s.violations(i));
  }
  for (const auto& x : s.probes) {
    row.insert(row.end(), {x.x(), x.y(), x.z()});
  }
  return row;
}

std::vector<TriangleMesh> SceneSimulation::meshes(int resolution) const {
  std::vector<TriangleMesh> result;
  for (int i = 0; i < system_.model_count(); ++i) {
    const SceneModel& spec = scene_.models[static_cast<size_t>(i)];
    const Model& model = system_.model(i);
    const Eigen::VectorXd q = system_.coordinates(i);
    const Eigen::Vector2d& scale = spec.resolution_scale;
    if (const auto* surface = dynamic_cast<const DNurbsSurface*>(&model)) {
      const NurbsSurface shape = surface->surface(q);
      result.push_back(tessellate_surface(
          shape, segments(resolution, scale.x(), shape.knots_u().is_periodic() ? 3 : 1),
          segments(resolution, scale.y(), shape.knots_v().is_periodic() ? 3 : 1), spec.name));
    } else if (const auto* curve = dynamic_cast<const DNurbsCurve*>(&model)) {
      result.push_back(tessellate_curve_tube(curve->curve(q),
                                             segments(4 * resolution, scale.x(), 3),
                                             tube_radii_[static_cast<size_t>(i)], 12, spec.name));
    } else if (const auto* terzopoulos = dynamic_cast<const TerzopoulosSurface*>(&model)) {
      result.push_back(
          grid_triangle_mesh(terzopoulos->grid(), terzopoulos->positions(q), spec.name));
    } else if (const auto* pde = dynamic_cast<const PdeSurface*>(&model)) {
      result.push_back(grid_triangle_mesh(pde->grid(), pde->positions(q), spec.name));
    } else if (const auto* snake = dynamic_cast<const Snake*>(&model)) {
      result.push_back(tessellate_curve_tube(polyline(snake->positions(q), snake->chain().closed()),
                                             segments(4 * resolution, scale.x(), 3),
                                             tube_radii_[static_cast<size_t>(i)], 12, spec.name));
    } else {
      // Superquadric: u latitude in [-pi/2, pi/2], v longitude in [-pi, pi) (periodic)
      const double pi = std::numbers::pi;
      result.push_back(sampled_mesh(model, q, -pi / 2, pi / 2, -pi, pi,
                                    segments(resolution, scale.x(), 2),
                                    segments(resolution, scale.y(), 3), true, spec.name));
    }
  }
  return result;
}

void SceneSimulation::set_coordinates(const Eigen::VectorXd& q) {
  system_.set_state(q, Eigen::VectorXd::Zero(system_.velocity_count()), system_.time());
}

std::optional<Shape> SceneSimulation::shape(int i) const {
  const Model& model = system_.model(i);
  const Eigen::VectorXd q = system_.coordinates(i);
  if (const auto* surface = dynamic_cast<const DNurbsSurface*>(&model)) {
    return Shape(surface->surface(q));
  }
  if (const auto* curve = dynamic_cast<const DNurbsCurve*>(&model)) {
    return Shape(curve->curve(q));
  }
  return std::nullopt;
}

Checkpoint SceneSimulation::checkpoint() const {
  Checkpoint c;
  c.scene = scene_.source;
  c.scene_hash = hash_;
  c.step = steps_;
  c.time = system_.time();
  c.coordinates = system_.coordinates();
  c.velocities = system_.velocities();
  c.accelerations_valid = system_.accelerations_valid();
  if (c.accelerations_valid) {
    c.accelerations = system_.accelerations();
  }
  return c;
}

void SceneSimulation::restore(const Checkpoint& checkpoint, const std::string& source) {
  if (checkpoint.scene_hash != hash_) {
    throw make_error(source, ": scene_hash: expected ", hash_, " (the hash of ", scene_.source,
                     "), got ", checkpoint.scene_hash,
                     ": the checkpoint belongs to another scene or the scene has changed");
  }
  if (checkpoint.coordinates.size() != system_.coordinate_count()) {
    throw make_error(source, ": q: expected ", system_.coordinate_count(), " coordinates, got ",
                     checkpoint.coordinates.size());
  }
  if (checkpoint.velocities.size() != system_.velocity_count()) {
    throw make_error(source, ": qd: expected ", system_.velocity_count(), " velocities, got ",
                     checkpoint.velocities.size());
  }
  system_.set_state(checkpoint.coordinates, checkpoint.velocities, checkpoint.time);
  if (checkpoint.accelerations_valid) {
    system_.set_accelerations(checkpoint.accelerations);
  }
  steps_ = checkpoint.step;
}

std::vector<SceneModelCost> SceneSimulation::cost() const {
  std::vector<SceneModelCost> costs;
  for (int i = 0; i < system_.model_count(); ++i) {
    const SceneModel& spec = scene_.models[static_cast<size_t>(i)];
    SceneModelCost c = model_cost(system_.model(i));
    c.name = spec.name;
    c.type = scene_model_type(spec);
    if (const auto naive = naive_variant(spec)) {
      const SceneModelCost naive_cost = model_cost(*build_model(naive->first));
      c.automatic_choice = naive->second;
      c.naive_active = naive_cost.velocities - naive_cost.fixed;
      c.naive_constant_matrices = naive_cost.constant_matrices;
      c.naive_solve_work = naive_cost.solve_work;
    }
    costs.push_back(c);
  }
  return costs;
}

}  // namespace dnurbs
