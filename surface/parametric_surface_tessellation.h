#pragma once
// Uniform tessellation of any ParametricSurface (a NURBS surface, a superquadric, a deformed
// surface, a dynamic model at a state) into a triangle mesh with normals and (u, v) texture
// coordinates, seams without duplicated vertices and one vertex per pole.

#include <string>

#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Samples the surface on the uniform grid of segments_u by segments_v cells over its domain
/// and splits each cell (a, b, c, d) = ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)) into the
/// triangles (a, b, c) and (a, c, d): the base mesh of the restricted mesh of Goldenstein et al.
/// 2005 section 4.2 (restricted_mesh.h), one basic block per cell.
///
/// Parameters are domain.u_at(i / segments_u) and domain.v_at(j / segments_v). A periodic
/// direction has `segments` samples (the seam is not duplicated); each pole is one vertex, and
/// the triangles that collapse there are dropped, so the cells next to a pole become a fan.
/// Vertex order: u outer, v inner, poles where first met. Normals are surface.unit_normal, uv the
/// parameters; triangles are wound so that (b - a) x (c - a) follows the surface's normal.
/// A closed surface (sphere, torus, superquadric) gives a watertight mesh: every edge in two
/// triangles. Throws Error if a resolution is below 1 (below 3 along a periodic direction).
TriangleMesh tessellate_surface(const ParametricSurface& surface, int segments_u, int segments_v,
                                std::string name = "surface");

}  // namespace dnurbs
