#pragma once
// Scene type "triangular_dnurbs_surface" (docs/scene-format.md): a triangular D-NURBS surface
// (dynamics/triangular/triangular_dnurbs_surface.h) over a triangulated domain, with its shape
// (a triangular_nurbs shape, inline or as a file, or a flat surface over a generated domain),
// material, settings and tessellation.

#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// A generated domain ("domain" key): the flat surface x(u, v) = (u, v, 0) of degree `degree`
/// over a triangulation of a rectangle, an L-shape or a square with a hole
/// (nurbs/triangulation_shapes.h), knot clouds by the standard placement.
struct SceneTriangularDomain {
  std::string shape = "rectangle";  ///< "rectangle", "l_shape" or "square_with_hole"
  /// rectangle: cells along u and v; l_shape, square_with_hole: cells per unit length (x).
  Eigen::Vector2i cells = Eigen::Vector2i(4, 4);
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();  ///< rectangle corners
  Eigen::Vector2d hi = Eigen::Vector2d::Ones();
  int degree = 2;
  double knot_radius = 0.3;  ///< KnotCloudSettings::radius
  bool operator==(const SceneTriangularDomain&) const = default;
};

struct SceneTriangularDNurbsSurface final : SceneModelSpec {
  std::optional<TriangularNurbsSurface> surface;  ///< the initial shape (read or generated)
  std::string shape_file;  ///< non-empty if the surface came from "shape_file" (written back so)
  std::optional<SceneTriangularDomain> domain;  ///< set if it came from "domain"
  DNurbsSurfaceMaterial material;               ///< constants (scene files give numbers)
  TriangularDNurbsSettings settings;

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "triangular_dnurbs_surface"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  /// Fixed weights: free weights.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// The flat surface of a generated domain; throws Error with the library's message.
TriangularNurbsSurface triangular_domain_surface(const SceneTriangularDomain& domain);

/// Reads the keys of a "triangular_dnurbs_surface" model.
std::unique_ptr<SceneModelSpec> read_triangular_dnurbs_surface_scene(const SceneReader& reader,
                                                                     const JsonValue& model,
                                                                     const std::string& path);

}  // namespace dnurbs
