#include "dnurbs/cad/step_geometry.h"

#include <StepGeom_BSplineCurveWithKnots.hxx>
#include <StepGeom_BSplineCurveWithKnotsAndRationalBSplineCurve.hxx>
#include <StepGeom_BSplineSurfaceWithKnots.hxx>
#include <StepGeom_BSplineSurfaceWithKnotsAndRationalBSplineSurface.hxx>
#include <StepGeom_CartesianPoint.hxx>
#include <StepGeom_HArray1OfCartesianPoint.hxx>
#include <StepGeom_HArray2OfCartesianPoint.hxx>
#include <StepGeom_RationalBSplineCurve.hxx>
#include <StepGeom_RationalBSplineSurface.hxx>
#include <StepGeom_SurfaceCurve.hxx>
#include <StepGeom_TrimmedCurve.hxx>
#include <StepShape_EdgeCurve.hxx>
#include <StepShape_FaceSurface.hxx>
#include <TColStd_HArray1OfInteger.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColStd_HArray2OfReal.hxx>

#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_form.h"

namespace dnurbs {
namespace {

/// The flat knot vector of a knot list with multiplicities.
KnotVector flat_knots(int degree, const Handle(TColStd_HArray1OfReal) & knots,
                      const Handle(TColStd_HArray1OfInteger) & multiplicities) {
  if (degree < 1 || degree > kMaxDegree) {
    throw make_error("degree ", degree, " is outside 1..", kMaxDegree);
  }
  if (knots.IsNull() || multiplicities.IsNull() || knots->Length() != multiplicities->Length()) {
    throw Error("the knot list and the multiplicity list differ in length");
  }
  std::vector<double> flat;
  for (int i = knots->Lower(); i <= knots->Upper(); ++i) {
    const int copies = multiplicities->Value(i - knots->Lower() + multiplicities->Lower());
    if (copies < 1 || copies > degree + 1) {
      throw make_error("knot multiplicity ", copies, " is outside 1..", degree + 1);
    }
    flat.insert(flat.end(), static_cast<size_t>(copies), knots->Value(i));
  }
  return {degree, std::move(flat)};
}

Eigen::Vector3d coordinates(const Handle(StepGeom_CartesianPoint) & point, double factor) {
  if (point.IsNull() || point->NbCoordinates() != 3) {
    throw Error("a control point is not a 3-D cartesian point");
  }
  return factor * Eigen::Vector3d(point->CoordinatesValue(1), point->CoordinatesValue(2),
                                  point->CoordinatesValue(3));
}

std::optional<Shape> curve_geometry(const Handle(StepGeom_Curve) & geometry, double factor) {
  if (const auto surface_curve = Handle(StepGeom_SurfaceCurve)::DownCast(geometry)) {
    return curve_geometry(surface_curve->Curve3d(), factor);
  }
  if (const auto trimmed = Handle(StepGeom_TrimmedCurve)::DownCast(geometry)) {
    return curve_geometry(trimmed->BasisCurve(), factor);  // the edge's range trims it
  }
  const auto rational =
      Handle(StepGeom_BSplineCurveWithKnotsAndRationalBSplineCurve)::DownCast(geometry);
  const auto plain = Handle(StepGeom_BSplineCurveWithKnots)::DownCast(geometry);
  if (rational.IsNull() && plain.IsNull()) {
    return std::nullopt;
  }
  const Handle(StepGeom_BSplineCurve) curve = rational.IsNull()
                                                  ? Handle(StepGeom_BSplineCurve)(plain)
                                                  : Handle(StepGeom_BSplineCurve)(rational);
  KnotVector knots =
      rational.IsNull()
          ? flat_knots(curve->Degree(), plain->Knots(), plain->KnotMultiplicities())
          : flat_knots(curve->Degree(), rational->Knots(), rational->KnotMultiplicities());
  const int count = curve->NbControlPointsList();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(count);
  for (int i = 0; i < count; ++i) {
    points.row(i) = coordinates(curve->ControlPointsListValue(i + 1), factor);
    if (!rational.IsNull()) {
      if (rational->NbWeightsData() != count) {
        throw make_error(rational->NbWeightsData(), " weights for ", count, " control points");
      }
      weights(i) = rational->WeightsDataValue(i + 1);
    }
  }
  return periodic_form(NurbsCurve(std::move(knots), std::move(points), std::move(weights)));
}

std::optional<Shape> surface_geometry(const Handle(StepGeom_Surface) & geometry, double factor) {
  const auto rational =
      Handle(StepGeom_BSplineSurfaceWithKnotsAndRationalBSplineSurface)::DownCast(geometry);
  const auto plain = Handle(StepGeom_BSplineSurfaceWithKnots)::DownCast(geometry);
  if (rational.IsNull() && plain.IsNull()) {
    return std::nullopt;
  }
  const Handle(StepGeom_BSplineSurfaceWithKnots) knotted =
      rational.IsNull() ? plain : rational->BSplineSurfaceWithKnots();
  const Handle(StepGeom_BSplineSurface) surface = rational.IsNull()
                                                      ? Handle(StepGeom_BSplineSurface)(plain)
                                                      : Handle(StepGeom_BSplineSurface)(rational);
  if (knotted.IsNull()) {
    throw Error("a rational B-spline surface without its knots");
  }
  KnotVector knots_u =
      flat_knots(surface->UDegree(), knotted->UKnots(), knotted->UMultiplicities());
  KnotVector knots_v =
      flat_knots(surface->VDegree(), knotted->VKnots(), knotted->VMultiplicities());
  const int count_u = surface->NbControlPointsListI();
  const int count_v = surface->NbControlPointsListJ();
  if (!rational.IsNull() && (rational->RationalBSplineSurface().IsNull() ||
                             rational->RationalBSplineSurface()->NbWeightsDataI() != count_u ||
                             rational->RationalBSplineSurface()->NbWeightsDataJ() != count_v)) {
    throw make_error("the weights do not match the ", count_u, " x ", count_v, " control points");
  }
  Eigen::MatrixX3d points(count_u * count_v, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(count_u * count_v);
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      points.row(i * count_v + j) =
          coordinates(surface->ControlPointsListValue(i + 1, j + 1), factor);
      if (!rational.IsNull()) {
        weights(i * count_v + j) =
            rational->RationalBSplineSurface()->WeightsDataValue(i + 1, j + 1);
      }
    }
  }
  return periodic_form(
      NurbsSurface(std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)));
}

}  // namespace

std::optional<Shape> step_bspline_geometry(const Handle(Standard_Transient) & entity,
                                           double length_factor) {
  if (const auto face = Handle(StepShape_FaceSurface)::DownCast(entity)) {
    return surface_geometry(face->FaceGeometry(), length_factor);
  }
  if (const auto edge = Handle(StepShape_EdgeCurve)::DownCast(entity)) {
    return curve_geometry(edge->EdgeGeometry(), length_factor);
  }
  if (const auto curve = Handle(StepGeom_Curve)::DownCast(entity)) {
    return curve_geometry(curve, length_factor);  // a curve of a GEOMETRIC_CURVE_SET
  }
  return std::nullopt;
}

}  // namespace dnurbs
