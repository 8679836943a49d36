#pragma once
// Uniform tessellation of NURBS surfaces into triangle meshes, and of NURBS curves into polylines
// and thin tubes.

#include <string>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Samples the surface on a uniform (u, v) grid of segments_u by segments_v cells over its
/// domain and splits each cell into two triangles.
///
/// Along an open direction there are segments + 1 samples, ends included. Along a periodic
/// direction there are `segments` samples and the last row of cells connects back to the first:
/// seam vertices are NOT duplicated, so a surface closed in both directions (a periodic torus)
/// gives a watertight mesh; the texture coordinate of a seam vertex is the domain start, so a
/// texture wraps there.
///
/// Vertex (i, j) (the i-th u sample, the j-th v sample) is row i * (#v samples) + j, u outer
/// like the control points. Normals are NurbsSurface::unit_normal, uv are the parameters (u, v);
/// triangles are oriented so that (b - a) x (c - a) points along Su x Sv.
/// Throws Error if a resolution is below 1 (below 3 along a periodic direction) or if a normal
/// is undefined.
TriangleMesh tessellate_surface(const NurbsSurface& surface, int segments_u, int segments_v,
                                std::string name = "surface");

/// Points C(u) at segments + 1 uniform parameters over the domain (segments for a periodic curve,
/// whose polyline closes implicitly): #samples by 3.
Eigen::MatrixX3d sample_curve(const NurbsCurve& curve, int segments);

/// A tube of the given radius around the curve: rings of `sides` vertices at the samples of
/// sample_curve, oriented by a rotation-minimizing (parallel transported) frame. A periodic
/// curve gives a closed tube (the frame's twist at the seam is spread along the curve); an open
/// curve gives an open tube without caps. uv holds (u, angle / 2 pi).
/// Throws Error if radius <= 0, sides < 3, segments < 1, or the tangent vanishes somewhere.
TriangleMesh tessellate_curve_tube(const NurbsCurve& curve, int segments, double radius,
                                   int sides = 12, std::string name = "curve");

}  // namespace dnurbs
