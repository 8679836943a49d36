#pragma once
// Tessellation of any Model at coordinates q (DESIGN.md, "The Model contract": "a tessellation
// of its current shape"): a surface model becomes a ParametricSurface through
// Model::position, meshed uniformly (surface/parametric_surface_tessellation.h) or adaptively
// (surface/restricted_mesh.h, seed 003 section 4); a curve model becomes a thin tube.

#include <string>

#include "dynamics/core/model.h"
#include "surface/parametric_surface.h"
#include "surface/triangle_mesh.h"

namespace dnurbs {

/// The (u, v) domain of a surface model with its closures: the NURBS surface's at q
/// (nurbs_parameter_domain) for DNurbsSurface, superquadric_parameter_domain() for
/// DeformableSuperquadricModel, the grid's [0, (nu - 1) h] x [0, (nv - 1) h] for
/// TerzopoulosSurface and PdeSurface. Throws Error for a curve or another model type (build the
/// ParametricSurface with an explicit domain instead).
ParameterDomain model_parameter_domain(const Model& model, ConstVectorRef q);

/// The orientation of the model's outward side: S_v x S_u for superquadrics, S_u x S_v else.
NormalOrientation model_normal_orientation(const Model& model);

/// The model's surface at q as a ParametricSurface over model_parameter_domain(model, q):
/// a DNurbsSurface gives its NURBS surface at q (exact normals); every other model gives
/// x(u, v) = Model::position(q, (u, v)) with normals from central differences of x
/// (ParametricSurface::difference_normal, pole limits included). The model (cloned) and q are
/// copied. Throws Error for a curve model or a q of the wrong size.
ParametricSurface model_surface(const Model& model, ConstVectorRef q);
/// The same over an explicit domain and orientation (any surface model).
ParametricSurface model_surface(const Model& model, ConstVectorRef q, const ParameterDomain& domain,
                                NormalOrientation orientation);

/// Resolution of tessellate_model.
struct ModelTessellationSettings {
  int segments_u = 32;  ///< cells along u (samples along a curve)
  int segments_v = 32;  ///< cells along v (surfaces only)
  /// Surfaces: 0 for the uniform mesh; > 0 refines it (as the base mesh of a RestrictedMesh)
  /// by the surface error criterion with this max error (seed 003 section 5.2.3).
  double max_error = 0.0;
  /// Surfaces, adaptive: the deepest bisection level below the base mesh.
  int max_level = 16;
  double tube_radius = 0.0;  ///< curves: tube radius; 0 picks 1 % of the samples' extent
  int tube_sides = 8;        ///< curves: vertices around the tube
};

/// A triangle mesh of the model at q with normals and (u, v) texture coordinates. Surfaces:
/// tessellate_surface(model_surface(model, q), segments_u, segments_v): seams without duplicated
/// vertices and one vertex per pole; with max_error > 0 that mesh refined adaptively until
/// every triangle's sampled error is within max_error (or max_level is reached). Curves: a tube
/// around the curve, for DNurbsCurve around its NURBS curve at q (tessellate_curve_tube), for Snake
/// around the polyline of Model::position at segments_u + 1 uniform s in [0, 1] (segments_u for a
/// closed chain). Throws Error for an unsupported model, a bad resolution or a q of the wrong size.
TriangleMesh tessellate_model(const Model& model, ConstVectorRef q,
                              const ModelTessellationSettings& settings = {},
                              std::string name = "model");

}  // namespace dnurbs
