#pragma once
// Tessellation of triangular NURBS surfaces and triangular D-NURBS models: uniform (every
// domain triangle split into s^2 congruent triangles) and adaptive (longest-edge bisection,
// Rivara, "Mesh refinement processes based on the generalized bisection of simplices", SIAM
// Journal on Numerical Analysis 21, 1984, driven by the chord error: the distance of the surface
// at a triangle's parametric centroid and edge midpoints from the flat triangle through its
// corners). Both meshes are conforming, share vertices along domain edges, carry per-vertex
// unit normals (x_u x x_v normalized) and the domain parameters as texture coordinates. For
// degree 1 (C^0) the normal jumps across knot segments; a shared vertex takes the normal from
// the domain triangle of the mesh triangle that created it.

#include <string>

#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "dnurbs/nurbs/triangular_nurbs_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// The surface over every domain triangle split into subdivisions^2 triangles (subdivisions
/// >= 1): #domain triangles * s^2 triangles. Throws Error for subdivisions outside 1..1024.
TriangleMesh tessellate_triangular_surface(const TriangularNurbsSurface& surface, int subdivisions,
                                           std::string name = "triangular_surface");

/// Starting from the domain triangulation, bisects (longest edge first, neighbours refined
/// along the longest-edge propagation path so that the mesh stays conforming) every triangle
/// whose chord error exceeds max_error (> 0), at most max_level bisections deep (1..40).
TriangleMesh tessellate_triangular_surface_adaptive(const TriangularNurbsSurface& surface,
                                                    double max_error, int max_level = 20,
                                                    std::string name = "triangular_surface");

/// The largest chord error of a mesh of the surface whose uv are domain parameters (as the
/// tessellations above produce): over every triangle, the distance between the surface and the
/// linear interpolation of the triangle's vertices at the parameters of a barycentric lattice
/// of `samples` (>= 2) intervals per edge.
double triangular_chord_error(const TriangularNurbsSurface& surface, const TriangleMesh& mesh,
                              int samples = 4);

/// The model's surface at q, uniformly (max_error <= 0) or adaptively tessellated.
TriangleMesh tessellate_triangular_model(const TriangularDNurbsSurface& model,
                                         const ConstVectorRef& q, int subdivisions,
                                         double max_error = 0.0,
                                         std::string name = "triangular_dnurbs_surface");

}  // namespace dnurbs
