#include "dnurbs/cad/occt_nurbs.h"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <algorithm>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_form.h"

namespace dnurbs {
namespace {

/// Distinct knots and multiplicities in Open CASCADE's form: of the whole vector (open) or of
/// one period with the seam multiplicity at both ends (periodic).
struct OcctKnots {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger multiplicities;
};

OcctKnots occt_knots(const KnotVector& basis) {
  std::vector<double> flat = basis.period_knots();
  if (basis.is_periodic()) {
    // The seam multiplicity s on both ends of the period: s copies of the start, then the
    // interior knots, then the end once (its multiplicity is set to s below).
    const int seam = basis.multiplicity(basis.domain_start());
    std::vector<double> interior;
    for (const double knot : flat) {
      if (knot != flat.front() && knot != flat.back()) {
        interior.push_back(knot);
      }
    }
    flat.assign(static_cast<size_t>(seam), basis.domain_start());
    flat.insert(flat.end(), interior.begin(), interior.end());
    flat.push_back(basis.domain_end());
  }
  std::vector<double> distinct;
  std::vector<int> counts;
  for (const double knot : flat) {
    if (!distinct.empty() && distinct.back() == knot) {
      ++counts.back();
    } else {
      distinct.push_back(knot);
      counts.push_back(1);
    }
  }
  if (basis.is_periodic()) {
    counts.back() = counts.front();
  }
  OcctKnots result{TColStd_Array1OfReal(1, static_cast<int>(distinct.size())),
                   TColStd_Array1OfInteger(1, static_cast<int>(distinct.size()))};
  for (size_t i = 0; i < distinct.size(); ++i) {
    result.knots(static_cast<int>(i) + 1) = distinct[i];
    result.multiplicities(static_cast<int>(i) + 1) = counts[i];
  }
  return result;
}

/// Open CASCADE's first span of a periodic basis is driven by poles 1..p+1; dnurbs's first
/// non-empty span [t_{p+a-1}, t_{p+a}), with a copies of the seam at the start of the period
/// list, by distinct control points a-1..a-1+p. Pole j (1-based) is control point
/// (j - 1 + pole_shift) mod n.
int pole_shift(const KnotVector& basis) {
  if (!basis.is_periodic()) {
    return 0;
  }
  const std::vector<double> period = basis.period_knots();
  return static_cast<int>(std::count(period.begin(), period.end(), period.front())) - 1;
}

/// Control point of Open CASCADE pole `pole` (1-based).
int control_point_of_pole(const KnotVector& basis, int pole) {
  return (pole - 1 + pole_shift(basis)) % basis.control_point_count();
}

/// The knot vector of an Open CASCADE basis: the flat knots of an open one, or the period list
/// (seam copies first, the end once) of a periodic one.
KnotVector dnurbs_knots(int degree, bool periodic, const TColStd_Array1OfReal& knots,
                        const TColStd_Array1OfInteger& multiplicities) {
  if (degree > kMaxDegree) {
    throw make_error("degree ", degree, " is above the highest dnurbs supports (", kMaxDegree, ")");
  }
  std::vector<double> flat;
  for (int i = knots.Lower(); i <= knots.Upper(); ++i) {
    const bool last = i == knots.Upper();
    const int copies = periodic && last ? 1 : multiplicities(i);
    flat.insert(flat.end(), static_cast<size_t>(copies), knots(i));
  }
  return periodic ? KnotVector::periodic(degree, flat) : KnotVector(degree, std::move(flat));
}

}  // namespace

opencascade::handle<Geom_BSplineCurve> to_occt(const NurbsCurve& curve) {
  const OcctKnots knots = occt_knots(curve.knots());
  const int count = curve.control_point_count();
  TColgp_Array1OfPnt poles(1, count);
  TColStd_Array1OfReal weights(1, count);
  for (int pole = 1; pole <= count; ++pole) {
    const int i = control_point_of_pole(curve.knots(), pole);
    const Eigen::Vector3d point = curve.control_points().row(i);
    poles(pole) = gp_Pnt(point.x(), point.y(), point.z());
    weights(pole) = curve.weights()(i);
  }
  if (curve.is_rational()) {
    return new Geom_BSplineCurve(poles, weights, knots.knots, knots.multiplicities, curve.degree(),
                                 curve.is_periodic());
  }
  return new Geom_BSplineCurve(poles, knots.knots, knots.multiplicities, curve.degree(),
                               curve.is_periodic());
}

opencascade::handle<Geom_BSplineSurface> to_occt(const NurbsSurface& surface) {
  const OcctKnots knots_u = occt_knots(surface.knots_u());
  const OcctKnots knots_v = occt_knots(surface.knots_v());
  const int count_u = surface.control_point_count_u();
  const int count_v = surface.control_point_count_v();
  TColgp_Array2OfPnt poles(1, count_u, 1, count_v);
  TColStd_Array2OfReal weights(1, count_u, 1, count_v);
  for (int pole_u = 1; pole_u <= count_u; ++pole_u) {
    for (int pole_v = 1; pole_v <= count_v; ++pole_v) {
      const int index =
          surface.control_point_index(control_point_of_pole(surface.knots_u(), pole_u),
                                      control_point_of_pole(surface.knots_v(), pole_v));
      const Eigen::Vector3d point = surface.control_points().row(index);
      poles(pole_u, pole_v) = gp_Pnt(point.x(), point.y(), point.z());
      weights(pole_u, pole_v) = surface.weights()(index);
    }
  }
  const bool periodic_u = surface.knots_u().is_periodic();
  const bool periodic_v = surface.knots_v().is_periodic();
  if (surface.is_rational()) {
    return new Geom_BSplineSurface(poles, weights, knots_u.knots, knots_v.knots,
                                   knots_u.multiplicities, knots_v.multiplicities,
                                   surface.degree_u(), surface.degree_v(), periodic_u, periodic_v);
  }
  return new Geom_BSplineSurface(poles, knots_u.knots, knots_v.knots, knots_u.multiplicities,
                                 knots_v.multiplicities, surface.degree_u(), surface.degree_v(),
                                 periodic_u, periodic_v);
}

NurbsCurve from_occt(const Geom_BSplineCurve& curve) {
  KnotVector knots =
      dnurbs_knots(curve.Degree(), curve.IsPeriodic(), curve.Knots(), curve.Multiplicities());
  const int count = curve.NbPoles();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights(count);
  for (int pole = 1; pole <= count; ++pole) {
    const int i = control_point_of_pole(knots, pole);
    points.row(i) << curve.Pole(pole).X(), curve.Pole(pole).Y(), curve.Pole(pole).Z();
    weights(i) = curve.Weight(pole);
  }
  return periodic_form(NurbsCurve(std::move(knots), std::move(points), std::move(weights)));
}

NurbsSurface from_occt(const Geom_BSplineSurface& surface) {
  KnotVector knots_u = dnurbs_knots(surface.UDegree(), surface.IsUPeriodic(), surface.UKnots(),
                                    surface.UMultiplicities());
  KnotVector knots_v = dnurbs_knots(surface.VDegree(), surface.IsVPeriodic(), surface.VKnots(),
                                    surface.VMultiplicities());
  const int count_u = surface.NbUPoles();
  const int count_v = surface.NbVPoles();
  Eigen::MatrixX3d points(count_u * count_v, 3);
  Eigen::VectorXd weights(count_u * count_v);
  for (int pole_u = 1; pole_u <= count_u; ++pole_u) {
    for (int pole_v = 1; pole_v <= count_v; ++pole_v) {
      const int row =
          control_point_of_pole(knots_u, pole_u) * count_v + control_point_of_pole(knots_v, pole_v);
      const gp_Pnt& pole = surface.Pole(pole_u, pole_v);
      points.row(row) << pole.X(), pole.Y(), pole.Z();
      weights(row) = surface.Weight(pole_u, pole_v);
    }
  }
  return periodic_form(
      NurbsSurface(std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)));
}

}  // namespace dnurbs
