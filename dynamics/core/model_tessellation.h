#pragma once
// The one tessellation path of every Model (DESIGN.md, "The Model contract": "a tessellation of
// its current shape"): tessellate_model checks q and calls Model::tessellate, whose default
// meshes a surface model through Model::parametric_surface uniformly
// (surface/parametric_surface_tessellation.h) or adaptively (surface/restricted_mesh.h; Deformation
// fields and adaptive meshes, section 4), and a curve model as a thin tube around its exact
// NURBS curve (or, without one, around the polyline of its sampled positions). Models whose shape
// is a mesh (grid surfaces: their node grid) or a polyline (snakes) override it.

#include <string>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Resolution of a model's tessellation.
struct ModelTessellationSettings {
  int segments_u = 32;  ///< cells along u (segments along a curve)
  int segments_v = 32;  ///< cells along v (surfaces only)
  /// Surfaces: 0 for the uniform mesh; > 0 refines it (as the base mesh of a RestrictedMesh)
  /// by the surface error criterion with this max error (Deformation fields and adaptive meshes,
  /// section 5.2.3).
  double max_error = 0.0;
  /// Surfaces, adaptive: the deepest bisection level below the base mesh.
  int max_level = 16;
  double tube_radius = 0.0;  ///< curves: tube radius; 0 picks curve_tube_radius(model, q)
  int tube_sides = 8;        ///< curves: vertices around the tube
};

/// A triangle mesh of the model at q with normals and (u, v) texture coordinates:
/// model.tessellate(q, settings, name). Surfaces: seams without duplicated vertices and one
/// vertex per pole; with max_error > 0 the uniform mesh refined adaptively until every
/// triangle's sampled error is within max_error (or max_level is reached). Curves: a tube of
/// segments_u + 1 rings (segments_u for a closed curve) of tube_sides vertices. Throws Error for a
/// bad resolution or a q of the wrong size.
TriangleMesh tessellate_model(const Model& model, ConstVectorRef q,
                              const ModelTessellationSettings& settings = {},
                              std::string name = "model");

/// The default tube radius of a curve model at q: 1 % of the diagonal of the bounding box of
/// 65 uniformly spaced points of the curve (1e-3 for a curve collapsed to a point).
double curve_tube_radius(const Model& model, ConstVectorRef q);

/// The fewest cells a tessellation of the domain needs along u (v = false) or v: 3 along a
/// periodic direction, 2 between two poles, 1 otherwise.
int minimum_segments(const ParameterDomain& domain, bool along_v);

/// x(u, v) = model.position(q, (u, v)) over `domain` as a ParametricSurface with difference
/// normals in the given orientation (the default of Model::parametric_surface). The model
/// (cloned) and q are copied. Throws Error unless the model is a surface model.
ParametricSurface sampled_model_surface(const Model& model, ConstVectorRef q,
                                        const ParameterDomain& domain,
                                        NormalOrientation orientation);

/// A tube around the polyline through `points` (#points by 3; closed when `closed`, which
/// needs at least 3 points), one ring per point: the tessellation of snakes and sampled curves.
TriangleMesh polyline_tube(const Eigen::MatrixX3d& points, bool closed, double radius, int sides,
                           std::string name);

}  // namespace dnurbs
