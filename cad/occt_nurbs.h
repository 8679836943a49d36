#pragma once
// Exact conversion between dnurbs NURBS shapes and Open CASCADE's B-spline geometry
// (Geom_BSplineCurve, Geom_BSplineSurface): knots, multiplicities, weights and control points
// carry over unchanged, so both evaluate to the same points (Piegl & Tiller, The NURBS Book,
// eq. 4.2 and 4.9 in both libraries).
//
// Open CASCADE stores a knot vector as distinct knots with multiplicities; a periodic basis as
// one period's distinct knots with equal first and last multiplicity (the seam multiplicity) and
// the n distinct poles, which is dnurbs's KnotVector::periodic with the seam copies at the start
// of the period list.

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Standard_Handle.hxx>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// The curve as an Open CASCADE B-spline curve, periodic if the curve is. Rational when the
/// curve is (Open CASCADE drops weights that are all equal).
opencascade::handle<Geom_BSplineCurve> to_occt(const NurbsCurve& curve);

/// The surface as an Open CASCADE B-spline surface (poles (i, j) = control point (i, j), u
/// first), periodic in each direction the surface is.
opencascade::handle<Geom_BSplineSurface> to_occt(const NurbsSurface& surface);

/// The Open CASCADE curve as a dnurbs curve. A non-periodic curve in the open form of a periodic
/// one (nurbs/periodic_form.h) comes back periodic. Throws Error naming the degree if it is
/// above kMaxDegree.
NurbsCurve from_occt(const Geom_BSplineCurve& curve);

/// The Open CASCADE surface as a dnurbs surface, periodic directions as for curves.
NurbsSurface from_occt(const Geom_BSplineSurface& surface);

}  // namespace dnurbs
