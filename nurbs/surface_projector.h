#pragma once
// The nearest point of a NURBS surface to a query point, found with a guarantee. The minimum of
// the distance over the closed domain lies on a boundary curve (or a corner, an end of one), on
// a C^0 crease curve (a knot of multiplicity >= degree), or at an interior stationary point of
// some Bezier patch. Boundary and crease curves are searched by CurveProjector; patches whose
// control points' bounding box is farther than the best distance so far are skipped, and in the
// others every stationary point is isolated by subdivision with exact exclusion and uniqueness
// tests and found by Newton's method (ProjectionPatch).

#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/curve_projector.h"
#include "dnurbs/nurbs/nearest_candidate.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/projection_patch.h"

namespace dnurbs {

/// The nearest point of a surface: its parameters (u, v), the point S(u, v) and |S - Q|.
struct SurfaceProjection {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// A surface prepared for many closest-point queries: its Bezier patches (one per pair of
/// non-empty spans) with their stationarity nets, and a CurveProjector for every boundary curve
/// of an open direction and every C^0 crease. Built once (O(#patches p^2 q^2)); immutable
/// afterwards, so one projector may serve queries from several threads. It keeps its own copy of
/// the surface.
class SurfaceProjector {
 public:
  explicit SurfaceProjector(NurbsSurface surface);

  const NurbsSurface& surface() const { return surface_; }
  /// Diagonal of the bounding box of the control points.
  double scale() const { return scale_; }

  /// The globally nearest surface point to `point` (finite, else Error). Ties (distances
  /// within kProjectionTieTolerance, nearest_candidate.h) go to the smallest (u, v), compared
  /// lexicographically; periodic directions report parameters in [domain_start, domain_end).
  /// `point` and `distance` are those of surface().point(u, v).
  ///
  /// The search is exhaustive up to 4000 box halvings per query (a few hundred suffice for the
  /// random rational surfaces of the tests); only a continuum of equidistant points, as for a
  /// query on an axis of revolution, reaches that, and any point of it is a nearest point.
  SurfaceProjection closest_point(const Eigen::Vector3d& point) const;

  /// Point inversion: the parameters of a point on the surface, to round-off. Throws Error
  /// naming the distance if `point` is farther than `tolerance` from the surface.
  Eigen::Vector2d invert(const Eigen::Vector3d& point, double tolerance) const;

 private:
  /// An iso-parameter curve: u = value (a curve in v) or v = value (a curve in u).
  struct Edge {
    CurveProjector projector;
    bool fixed_u = true;
    double value = 0.0;
  };
  using Best = NearestCandidate<Eigen::Vector2d>;
  class PatchVisitor;

  void add_edges(bool fixed_u, const Eigen::MatrixXd& homogeneous);
  Eigen::Vector2d to_parameter(const ProjectionPatch& patch, double s, double t) const;

  NurbsSurface surface_;
  double scale_ = 0.0;
  std::vector<ProjectionPatch> patches_;
  std::vector<Edge> edges_;
};

}  // namespace dnurbs
