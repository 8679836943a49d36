#pragma once
// Refinement of swung surfaces by knot insertion (Piegl & Tiller, The NURBS Book, A5.4) into
// the profile and the trajectory: the same surface with more control points, so that a swung
// D-NURBS model of it has more coordinates to sculpt with (Qin & Terzopoulos, Dynamic NURBS
// swung surfaces for physics-based shape design, CAD 27(2) 1995).

#include "dnurbs/nurbs/swung_surface.h"

namespace dnurbs {

/// The surface with `profile_knots` knots inserted uniformly inside every non-empty span of the
/// profile (at t_k + (t_{k+1} - t_k) i / (profile_knots + 1), i = 1..profile_knots) and
/// `trajectory_knots` inside every non-empty span of the trajectory; alpha is kept. Inserting a
/// knot changes no point of a curve, so the surface is unchanged (to rounding); a periodic
/// curve stays periodic. A curve of m control points over S spans gets m + S k of them
/// (periodic: m + S k as well). Throws Error for a negative count.
SwungSurface refine_swung_surface(const SwungSurface& surface, int profile_knots,
                                  int trajectory_knots);

}  // namespace dnurbs
