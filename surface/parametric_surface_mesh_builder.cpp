#include "dnurbs/surface/parametric_surface_mesh_builder.h"

#include <utility>

namespace dnurbs {

ParametricSurfaceMeshBuilder::ParametricSurfaceMeshBuilder(const ParametricSurface& surface)
    : surface_(&surface) {}

int ParametricSurfaceMeshBuilder::add_vertex(double u, double v) {
  const ParameterDomain& domain = surface_->domain();
  const int pole = domain.pole_at(u, v);
  if (pole >= 0) {
    int& vertex = pole_vertex_[static_cast<size_t>(pole)];
    if (vertex < 0) {
      // One vertex per pole, at a canonical parameter (the pole edge's start), so that every
      // mesh of the surface gives the pole the same (u, v), point and normal
      const double pu = pole < 2 ? u : domain.u_min;
      const double pv = pole < 2 ? domain.v_min : v;
      vertex = push(pu, pv, surface_->point(pu, pv), surface_->unit_normal(pu, pv));
    }
    return vertex;
  }
  return push(u, v, surface_->point(u, v), surface_->unit_normal(u, v));
}

int ParametricSurfaceMeshBuilder::add_vertex(double u, double v, const Eigen::Vector3d& point,
                                             const Eigen::Vector3d& normal) {
  if (surface_->domain().pole_at(u, v) >= 0) {
    return add_vertex(u, v);
  }
  return push(u, v, point, normal);
}

int ParametricSurfaceMeshBuilder::push(double u, double v, const Eigen::Vector3d& point,
                                       const Eigen::Vector3d& normal) {
  const int index = vertex_count();
  points_.push_back(point);
  normals_.push_back(normal);
  parameters_.emplace_back(u, v);
  return index;
}

void ParametricSurfaceMeshBuilder::add_triangle(int a, int b, int c) {
  if (a == b || b == c || c == a) {
    return;  // collapsed at a pole: its (u, v) area maps onto an edge of its neighbors
  }
  if (surface_->orientation() == NormalOrientation::kSuCrossSv) {
    triangles_.emplace_back(a, b, c);
  } else {
    triangles_.emplace_back(a, c, b);
  }
}

TriangleMesh ParametricSurfaceMeshBuilder::build(std::string name) const {
  TriangleMesh mesh;
  mesh.name = std::move(name);
  const int count = vertex_count();
  mesh.vertices.resize(count, 3);
  mesh.normals.resize(count, 3);
  mesh.uv.resize(count, 2);
  for (int k = 0; k < count; ++k) {
    mesh.vertices.row(k) = points_[static_cast<size_t>(k)].transpose();
    mesh.normals.row(k) = normals_[static_cast<size_t>(k)].transpose();
    mesh.uv.row(k) = parameters_[static_cast<size_t>(k)].transpose();
  }
  mesh.triangles.resize(static_cast<int>(triangles_.size()), 3);
  for (size_t f = 0; f < triangles_.size(); ++f) {
    mesh.triangles.row(static_cast<int>(f)) = triangles_[f].transpose();
  }
  return mesh;
}

}  // namespace dnurbs
