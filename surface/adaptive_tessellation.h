#pragma once
// Adaptive tessellation (Goldenstein et al. 2005, section 5): the three refinement strategies of
// section 5.2 as RefinementTests for the restricted mesh, the surface error of eqs 5-7, and the
// driver that refines a base mesh and returns a TriangleMesh.

#include <limits>
#include <string>

#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/restricted_mesh.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Barycentric sampling order of the surface error: the points (i, j, k) / n, i + j + k = n.
inline constexpr int kDefaultErrorSampleOrder = 8;

/// Unconditional refinement (Goldenstein et al. 2005, section 5.2.1): every triangle below `depth`
/// bisections. Throws Error if depth < 0.
RefinementTest depth_criterion(int depth);

/// A normals-based refinement on the surface's normals (a variant of Goldenstein et al. 2005,
/// section 5.2.2, which looks at the mesh's facets: normals_criterion): a triangle is split while
/// the largest angle between two of its vertex normals (the surface's unit normals) exceeds
/// `max_angle` (radians). Throws Error unless 0 < max_angle <= pi.
RefinementTest normal_angle_criterion(double max_angle);

/// Normals-based refinement as Goldenstein et al. 2005, section 5.2.2 define it, on the current
/// mesh's facets: a triangle is split while one of its edges is a ridge or valley (the facet
/// normals of the two triangles sharing it, RestrictedMesh::facet_normal, are more than
/// `ridge_angle` apart) or ends in a jagged angle (the facet normals averaged around its two end
/// points, RestrictedMesh::averaged_facet_normal, are more than `endpoint_angle` apart). A zero
/// normal (a facet collapsed at a pole) takes part in no comparison. Angles in radians; pi turns
/// its half of the test off. The test needs the triangle's mesh: it throws Error for a geometry
/// without one. Throws Error unless both angles are in (0, pi].
RefinementTest normals_criterion(double ridge_angle, double endpoint_angle);

/// The parametric error of a triangle or a mesh (Goldenstein et al. 2005, eqs. 5-7): at (u, v),
/// eps(u, v) = |S(u, v) - P(u, v)| with P the linear interpolation of the vertex points in
/// (u, v) (the piecewise-linear mesh); `max` is its largest sample (eq 7), `mean` its integral
/// over the (u, v) area divided by that area (eq 6).
struct SurfaceError {
  double max = 0.0;
  double mean = 0.0;
};

/// eps sampled at the barycentric points of order `sample_order` (>= 1): max over the points,
/// mean by the composite vertex rule on the n^2 sub-triangles (weights 1, 3, 6 over 3 n^2 for
/// corner, edge and interior points). Throws Error if sample_order < 1.
SurfaceError triangle_surface_error(const ParametricSurface& surface,
                                    const RestrictedTriangleGeometry& triangle,
                                    int sample_order = kDefaultErrorSampleOrder);

/// Surface contour error-based refinement (Goldenstein et al. 2005, section 5.2.3): a triangle is
/// split while its sampled max error exceeds `max_error` or its mean error exceeds `mean_error`
/// (infinity: no mean bound). Throws Error unless max_error > 0 and mean_error > 0 (not NaN) and
/// sample_order >= 1.
RefinementTest surface_error_criterion(const ParametricSurface& surface, double max_error,
                                       double mean_error = std::numeric_limits<double>::infinity(),
                                       int sample_order = kDefaultErrorSampleOrder);

/// The error of a whole restricted mesh against its surface: the max of the triangles' max, and
/// the (u, v)-area weighted mean of their means, each triangle sampled at `sample_order`.
SurfaceError mesh_surface_error(const RestrictedMesh& mesh, int sample_order);

/// The coarsest uniform mesh of (scale base_cells_u) by (scale base_cells_v) cells, scale >= 1,
/// whose sampled max error (mesh_surface_error at sample_order) is within max_error: the
/// reference that adaptive tessellation is measured against.
struct UniformTessellationChoice {
  int cells_u = 0;
  int cells_v = 0;
  int vertices = 0;  ///< of the output mesh (poles merged)
  SurfaceError error;
};

/// Finds the scale by doubling, then bisection (the error falls with the scale for the smooth
/// surfaces this is meant for). Throws Error unless max_error > 0, or if the bound is not met
/// below RestrictedMesh::kMaxBaseCells cells.
UniformTessellationChoice coarsest_uniform_tessellation(
    const ParametricSurface& surface, int base_cells_u, int base_cells_v, double max_error,
    int sample_order = kDefaultErrorSampleOrder);

/// Error-based adaptive refinement (surface_error_criterion(surface, max_error)) from the base
/// grid that needs the fewest vertices. Bisection halves a triangle's area per level, so a mesh
/// refined from one base meets an error bound with up to twice the vertices it needs (the bound
/// falls between two levels), and the base cells' aspect ratio decides which edges are split
/// first. The candidates are the base grids of round(base_cells_u s) by round(base_cells_v s r)
/// cells, s = 2^(k/4) (k = 0..3) and r = 2^(l/4) (l = -2..2), at least 3 cells along a periodic
/// direction. The error is O(h^2) and h halves every two levels, so the bound 16 max_error
/// sits at the same place between levels four levels up: each candidate is refined to that
/// bound (about 1/16 of the work), and the one with the fewest output vertices (ties: the
/// first) is refined to max_error. Throws Error as surface_error_criterion and RestrictedMesh.
RestrictedMesh refine_to_surface_error_from_best_base(
    const ParametricSurface& surface, double max_error, int base_cells_u, int base_cells_v,
    int max_level = RestrictedMesh::kDefaultMaxLevel, int sample_order = kDefaultErrorSampleOrder);

/// Refines the base mesh of base_cells_u by base_cells_v cells (RestrictedMesh) by the test,
/// to at most `max_level` bisections, and returns the mesh with poles merged
/// (RestrictedMesh::to_triangle_mesh).
TriangleMesh tessellate_adaptive(const ParametricSurface& surface,
                                 const RefinementTest& needs_refinement, int base_cells_u,
                                 int base_cells_v, int max_level = RestrictedMesh::kDefaultMaxLevel,
                                 std::string name = "surface");

}  // namespace dnurbs
