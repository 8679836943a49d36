#include "bench_scenes.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs::bench {

namespace {

Eigen::VectorXd greville(const KnotVector& knots) {
  const int p = knots.degree();
  Eigen::VectorXd result(knots.control_point_count());
  for (int i = 0; i < result.size(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= p; ++k) {
      sum += knots[i + k];
    }
    result[i] = sum / p;
  }
  return result;
}

}  // namespace

DNurbsCurve clamped_string(int control_points, WeightMode mode, double rigidity,
                           int quadrature_points) {
  const KnotVector knots = KnotVector::clamped_uniform(3, control_points);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(control_points, 3);
  points.col(0) = greville(knots);
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.rigidity = rigidity;
  DNurbsSettings settings;
  settings.weight_mode = mode;
  settings.quadrature_points = quadrature_points;
  DNurbsCurve model(NurbsCurve(knots, points), material, settings);
  model.fix_control_point(0);
  model.fix_control_point(control_points - 1);
  return model;
}

DNurbsSurface clamped_membrane(int per_side, WeightMode mode, double damping,
                               int quadrature_points) {
  const KnotVector knots = KnotVector::clamped_uniform(3, per_side);
  const Eigen::VectorXd g = greville(knots);
  Eigen::MatrixX3d points(per_side * per_side, 3);
  for (int i = 0; i < per_side; ++i) {
    for (int j = 0; j < per_side; ++j) {
      points.row(i * per_side + j) << g[i], g[j], 0.0;
    }
  }
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 1e-3;
  material.b02 = 1e-3;
  material.damping_density = damping;
  DNurbsSettings settings;
  settings.weight_mode = mode;
  settings.quadrature_points = quadrature_points;
  DNurbsSurface model(NurbsSurface(knots, knots, points), material, settings);
  model.fix_border();
  return model;
}

System spinning_superquadric(const DeformableSuperquadricParts& parts) {
  using Shape = SuperquadricShapeParameter;
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 1.5, 1.0, 0.6, 0.7, 1.3, 0, 0, 0, 0, 0, 0, 0, 0;
  shape[Shape::kBendAmplitude] = 0.2;
  shape[Shape::kBendFrequency] = 0.5;
  DeformableSuperquadricSettings settings;
  settings.parts = parts;
  const DeformableSuperquadricModel model(
      shape, Eigen::Vector3d(0.1, 0.2, 0.3),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized())), settings);
  System system(model);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(model.velocity_count());
  qd.head<6>() << 0.2, -0.1, 0.05, 0.4, 2.0, -0.3;
  system.set_velocities(0, qd);
  return system;
}

double smooth_ramp(double time, double ramp_time) {
  if (time >= ramp_time) {
    return 1.0;
  }
  return 0.5 * (1.0 - std::cos(std::numbers::pi * time / ramp_time));
}

System pushed_terzopoulos_sheet(double ramp_time) {
  const int n = 9;
  const Grid grid(n, n, 1.0 / (n - 1));
  TerzopoulosMaterial material;
  material.damping_density = 0.5;
  material.eta << 0.1, 0.0, 0.0, 0.1;
  material.xi << 1e-3, 1e-3, 1e-3, 1e-3;
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  sheet.fix_border();
  System system(sheet);
  system.add_force(0, point_force(grid.parameter(n / 2, n / 2), [ramp_time](double t) {
                     return Eigen::Vector3d(0, 0, -0.01 * smooth_ramp(t, ramp_time));
                   }));
  return system;
}

System pushed_pde_surface(int nodes_per_side, bool region, double ramp_time) {
  const Grid grid(nodes_per_side, nodes_per_side, 1.0 / (nodes_per_side - 1));
  PdeSurfaceMaterial material;
  material.damping_density = 20.0;
  const Eigen::Vector3d centre(0.5, 0.5, 0.0);
  std::vector<DeformationRegion> regions;
  if (region) {
    regions.push_back({centre, 0.25});
  }
  const PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material,
                           regions);
  System system(surface);
  const std::vector<int> nodes = surface.nodes_within(centre, 0.08);
  const Eigen::Vector3d per_node(0, 0, 1.0 / static_cast<double>(nodes.size()));
  system.add_force(0, control_point_force(nodes, [per_node, ramp_time](double t) {
                     return Eigen::Vector3d(per_node * smooth_ramp(t, ramp_time));
                   }));
  return system;
}

}  // namespace dnurbs::bench
