#include "dnurbs/nurbs/shape_generators.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/LU>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/degree_elevation.h"
#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

void check_count_and_degree(int count, int degree, const char* what) {
  if (degree < 1 || degree > kMaxDegree) {
    throw make_error(what, " degree must be in 1..", kMaxDegree, ", got ", degree);
  }
  if (count < degree + 1) {
    throw make_error(what, " needs at least degree + 1 = ", degree + 1, " control points, got ",
                     count);
  }
}

// Clamped uniform knots over [0, length] with the given count and degree.
KnotVector greville_knots(int count, int degree, double length, const char* what) {
  check_count_and_degree(count, degree, what);
  check_shape_size(length, what);
  return KnotVector::clamped_uniform(degree, count, 0.0, length);
}

// The knots of every interior breakpoint of `knots` split into `parts` equal pieces.
std::vector<double> split_knots(const KnotVector& knots, int parts) {
  if (parts < 1) {
    throw make_error("span parts must be >= 1, got ", parts);
  }
  std::vector<double> inserted;
  for (const int span : knots.non_empty_spans()) {
    const double a = knots[span];
    const double b = knots[span + 1];
    for (int k = 1; k < parts; ++k) {
      inserted.push_back(a + (b - a) * k / parts);
    }
  }
  return inserted;
}

// A section of a loft with its knots mapped onto [start, end], every knot within a relative 1e-12
// of a knot of an earlier section snapped onto it, so that merging sees equal knots as equal.
NurbsCurve remapped_section(const NurbsCurve& section, double start, double end,
                            std::vector<double>& seen) {
  const KnotVector& knots = section.knots();
  const double a = knots.domain_start();
  const double b = knots.domain_end();
  const double tolerance = 1e-12 * (end - start);
  std::vector<double> mapped;
  for (const double t : knots.knots()) {
    double x = t == a ? start : t == b ? end : start + (t - a) * (end - start) / (b - a);
    const auto near = std::find_if(seen.begin(), seen.end(),
                                   [&](double s) { return std::abs(s - x) <= tolerance; });
    if (near != seen.end()) {
      x = *near;
    } else {
      seen.push_back(x);
    }
    mapped.push_back(x);
  }
  // Scaling all weights leaves the curve unchanged; a geometric mean of 1 keeps the weights of
  // different sections comparable, so that interpolating them along v overshoots less.
  const double mean = std::exp(section.weights().array().log().mean());
  return NurbsCurve(KnotVector(knots.degree(), mapped), section.control_points(),
                    section.weights() / mean);
}

// The knots of `target` (sorted, with multiplicities) that `knots` lacks.
std::vector<double> missing_knots(const std::vector<double>& knots,
                                  const std::vector<double>& target) {
  std::vector<double> missing;
  std::set_difference(target.begin(), target.end(), knots.begin(), knots.end(),
                      std::back_inserter(missing));
  return missing;
}

// Averaged chord-length parameters of the sections along v (Piegl & Tiller eq. 9.5 per control
// point column, averaged over the columns that move; uniform if none does), in [0, 1].
std::vector<double> chord_length_parameters(const std::vector<NurbsCurve>& sections) {
  const int n = static_cast<int>(sections.size());
  const int columns = sections.front().control_point_count();
  std::vector<double> parameters(static_cast<size_t>(n), 0.0);
  int moving = 0;
  for (int i = 0; i < columns; ++i) {
    std::vector<double> chords(static_cast<size_t>(n), 0.0);
    double total = 0.0;
    for (int k = 1; k < n; ++k) {
      const double chord = (sections[static_cast<size_t>(k)].control_points().row(i) -
                            sections[static_cast<size_t>(k - 1)].control_points().row(i))
                               .norm();
      total += chord;
      chords[static_cast<size_t>(k)] = total;
    }
    if (total > 0.0) {
      ++moving;
      for (int k = 1; k < n; ++k) {
        parameters[static_cast<size_t>(k)] += chords[static_cast<size_t>(k)] / total;
      }
    }
  }
  for (int k = 1; k < n; ++k) {
    parameters[static_cast<size_t>(k)] =
        moving > 0 ? parameters[static_cast<size_t>(k)] / moving : static_cast<double>(k) / (n - 1);
  }
  parameters.back() = 1.0;
  return parameters;
}

// Clamped knots of degree q over [0, 1] by averaging the parameters (Piegl & Tiller eq. 9.8).
KnotVector averaged_knots(const std::vector<double>& parameters, int degree) {
  const int n = static_cast<int>(parameters.size());
  std::vector<double> knots(static_cast<size_t>(degree + 1), 0.0);
  for (int j = 1; j < n - degree; ++j) {
    double sum = 0.0;
    for (int i = j; i < j + degree; ++i) {
      sum += parameters[static_cast<size_t>(i)];
    }
    knots.push_back(sum / degree);
  }
  knots.insert(knots.end(), static_cast<size_t>(degree + 1), 1.0);
  return KnotVector(degree, std::move(knots));
}

}  // namespace

std::vector<double> greville_abscissae(const KnotVector& knots) {
  if (knots.is_periodic()) {
    throw make_error("Greville abscissae need an open knot vector, got a periodic one");
  }
  const int p = knots.degree();
  std::vector<double> abscissae;
  for (int i = 0; i < knots.control_point_count(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= p; ++k) {
      sum += knots[i + k];
    }
    abscissae.push_back(sum / p);
  }
  return abscissae;
}

NurbsCurve greville_line(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                         int control_points, int degree, std::optional<double> domain) {
  if (!start.allFinite() || !end.allFinite()) {
    throw make_error("line end points must be finite");
  }
  const double length = (end - start).norm();
  check_shape_size(length, "line length");
  const double extent = domain.value_or(length);
  KnotVector knots = greville_knots(control_points, degree, extent, "line domain");
  const Eigen::Vector3d step = (end - start) / extent;
  const std::vector<double> abscissae = greville_abscissae(knots);
  Eigen::MatrixX3d points(control_points, 3);
  for (int i = 0; i < control_points; ++i) {
    points.row(i) = (start + abscissae[static_cast<size_t>(i)] * step).transpose();
  }
  return NurbsCurve(std::move(knots), std::move(points));
}

NurbsCurve straight_profile(double x0, double z0, double x1, double z1, int count,
                            std::optional<double> domain) {
  if (count < 2) {
    throw make_error("a straight profile needs at least 2 control points, got ", count);
  }
  return greville_line({x0, 0.0, z0}, {x1, 0.0, z1}, count, std::min(3, count - 1), domain);
}

NurbsSurface greville_plane(const Eigen::Vector2d& size, const Eigen::Vector2i& control_points,
                            const Eigen::Vector2i& degree, const Eigen::Vector3d& origin,
                            const std::optional<Eigen::Vector2d>& domain) {
  if (!origin.allFinite()) {
    throw make_error("plane origin must be finite");
  }
  check_shape_size(size.x(), "plane size x");
  check_shape_size(size.y(), "plane size y");
  const Eigen::Vector2d extent = domain.value_or(size);
  KnotVector knots_u = greville_knots(control_points.x(), degree.x(), extent.x(), "plane domain x");
  KnotVector knots_v = greville_knots(control_points.y(), degree.y(), extent.y(), "plane domain y");
  const Eigen::Vector2d scale = size.cwiseQuotient(extent);
  const std::vector<double> xi = greville_abscissae(knots_u);
  const std::vector<double> eta = greville_abscissae(knots_v);
  Eigen::MatrixX3d points(control_points.x() * control_points.y(), 3);
  for (int i = 0; i < control_points.x(); ++i) {
    for (int j = 0; j < control_points.y(); ++j) {
      points.row(i * control_points.y() + j) =
          (origin + Eigen::Vector3d(scale.x() * xi[static_cast<size_t>(i)],
                                    scale.y() * eta[static_cast<size_t>(j)], 0.0))
              .transpose();
    }
  }
  return NurbsSurface(std::move(knots_u), std::move(knots_v), std::move(points));
}

NurbsSurface box(const Eigen::Vector3d& size) {
  check_shape_size(size.x(), "box size x");
  check_shape_size(size.y(), "box size y");
  check_shape_size(size.z(), "box size z");
  // Profile (radial factor, height) from the bottom centre over the side to the top centre, and
  // the square section from corner (+x, +y) counter-clockwise back to it.
  const double radial[4] = {0.0, 1.0, 1.0, 0.0};
  const double height[4] = {0.0, 0.0, size.z(), size.z()};
  const double hx = size.x() / 2;
  const double hy = size.y() / 2;
  const double square[5][2] = {{hx, hy}, {-hx, hy}, {-hx, -hy}, {hx, -hy}, {hx, hy}};
  Eigen::MatrixX3d points(4 * 5, 3);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 5; ++j) {
      points.row(i * 5 + j) << radial[i] * square[j][0], radial[i] * square[j][1], height[i];
    }
  }
  return NurbsSurface(KnotVector(1, {0, 0, 1, 2, 3, 3}), KnotVector(1, {0, 0, 1, 2, 3, 4, 4}),
                      std::move(points));
}

NurbsSurface cylinder(double radius, double height, int profile_control_points) {
  check_shape_size(radius, "cylinder radius");
  check_shape_size(height, "cylinder height");
  return surface_of_revolution(
      straight_profile(radius, 0.0, radius, height, profile_control_points));
}

NurbsSurface cone(double radius, double height, int profile_control_points) {
  check_shape_size(radius, "cone radius");
  check_shape_size(height, "cone height");
  return surface_of_revolution(straight_profile(radius, 0.0, 0.0, height, profile_control_points));
}

NurbsSurface revolve(const NurbsCurve& profile, double angle) {
  constexpr double kFullTurn = 2 * std::numbers::pi;
  if (!std::isfinite(angle) || !(angle > 0.0) || angle > kFullTurn * (1 + 1e-15)) {
    throw make_error("revolution angle must be in (0, 2 pi], got ", angle);
  }
  if (profile.is_periodic()) {
    throw make_error("revolve needs an open profile curve");
  }
  if (angle >= kFullTurn) {
    return surface_of_revolution(profile);
  }
  // Piegl & Tiller A8.1: arcs of at most a quarter turn, each one rational quadratic Bezier
  // segment with middle weight cos(delta / 2) and middle point at radius r / cos(delta / 2).
  const int arcs = static_cast<int>(std::ceil(angle / (std::numbers::pi / 2) - 1e-12));
  const double delta = angle / arcs;
  const double middle_weight = std::cos(delta / 2);
  const int columns = 2 * arcs + 1;
  std::vector<double> knots = {0, 0, 0};
  for (int k = 1; k < arcs; ++k) {
    knots.push_back(static_cast<double>(k) / arcs);
    knots.push_back(static_cast<double>(k) / arcs);
  }
  knots.insert(knots.end(), {1, 1, 1});
  const int rows = profile.control_point_count();
  Eigen::MatrixX3d points(rows * columns, 3);
  Eigen::VectorXd weights(rows * columns);
  for (int i = 0; i < rows; ++i) {
    const Eigen::Vector3d p = profile.control_points().row(i).transpose();
    const double radius = std::hypot(p.x(), p.y());
    const double start = std::atan2(p.y(), p.x());
    for (int j = 0; j < columns; ++j) {
      const bool middle = j % 2 == 1;
      const double r = middle ? radius / middle_weight : radius;
      const double theta = start + delta * j / 2;
      points.row(i * columns + j) << r * std::cos(theta), r * std::sin(theta), p.z();
      weights[i * columns + j] = profile.weights()[i] * (middle ? middle_weight : 1.0);
    }
  }
  return NurbsSurface(profile.knots(), KnotVector(2, std::move(knots)), std::move(points),
                      std::move(weights));
}

NurbsSurface extrude(const NurbsCurve& curve, const Eigen::Vector3d& direction) {
  if (!direction.allFinite()) {
    throw make_error("extrusion direction must be finite");
  }
  const double length = direction.norm();
  check_shape_size(length, "extrusion length");
  const int n = curve.control_point_count();
  Eigen::MatrixX3d points(n * 2, 3);
  Eigen::VectorXd weights(n * 2);
  for (int i = 0; i < n; ++i) {
    points.row(i * 2) = curve.control_points().row(i);
    points.row(i * 2 + 1) = curve.control_points().row(i) + direction.transpose();
    weights[i * 2] = weights[i * 2 + 1] = curve.weights()[i];
  }
  return NurbsSurface(curve.knots(), KnotVector(1, {0, 0, length, length}), std::move(points),
                      std::move(weights));
}

NurbsSurface loft(const std::vector<NurbsCurve>& sections, int degree_v,
                  std::vector<double>* section_parameters, long long max_control_points) {
  const int n = static_cast<int>(sections.size());
  if (n < 2) {
    throw make_error("a loft needs at least 2 sections, got ", n);
  }
  if (degree_v < 1 || degree_v > kMaxDegree) {
    throw make_error("loft degree must be in 1..", kMaxDegree, ", got ", degree_v);
  }
  int degree_u = 1;
  for (int k = 0; k < n; ++k) {
    if (sections[static_cast<size_t>(k)].is_periodic()) {
      throw make_error("loft section ", k, " is periodic; lofts take open sections");
    }
    degree_u = std::max(degree_u, sections[static_cast<size_t>(k)].degree());
  }
  // Compatible sections: one domain, one degree, one knot vector (Piegl & Tiller 10.3)
  const double start = sections.front().knots().domain_start();
  const double end = sections.front().knots().domain_end();
  std::vector<double> seen;
  std::vector<NurbsCurve> compatible;
  std::vector<double> merged;
  for (const NurbsCurve& section : sections) {
    NurbsCurve c =
        elevate_degree(remapped_section(section, start, end, seen), degree_u - section.degree());
    std::vector<double> merged_now;
    std::set_union(merged.begin(), merged.end(), c.knots().knots().begin(), c.knots().knots().end(),
                   std::back_inserter(merged_now));
    merged = std::move(merged_now);
    compatible.push_back(std::move(c));
  }
  const long long count = static_cast<long long>(merged.size() - degree_u - 1) * n;
  if (count > max_control_points) {
    throw make_error("the loft would make ", count, " control points (",
                     merged.size() - degree_u - 1, " per section, ", n,
                     " sections), more than the limit of ", max_control_points);
  }
  for (NurbsCurve& c : compatible) {
    c = refine_knots(c, missing_knots(c.knots().knots(), merged));
  }
  // Interpolate every homogeneous column along v (Piegl & Tiller eqs. 9.5, 9.8, A9.1)
  const int q = std::min(degree_v, n - 1);
  const std::vector<double> parameters = chord_length_parameters(compatible);
  const KnotVector knots_v = averaged_knots(parameters, q);
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(n, n);
  BasisValues values;
  for (int k = 0; k < n; ++k) {
    const double v = parameters[static_cast<size_t>(k)];
    const int span = knots_v.find_span(v);
    basis_functions(knots_v, span, v, values);
    for (int j = 0; j <= q; ++j) {
      basis(k, span - q + j) = values[j];
    }
  }
  const int columns = compatible.front().control_point_count();
  Eigen::MatrixXd homogeneous(n, columns * 4);
  for (int k = 0; k < n; ++k) {
    const NurbsCurve& c = compatible[static_cast<size_t>(k)];
    for (int i = 0; i < columns; ++i) {
      const double w = c.weights()[i];
      homogeneous.block<1, 3>(k, i * 4) = w * c.control_points().row(i);
      homogeneous(k, i * 4 + 3) = w;
    }
  }
  const Eigen::MatrixXd net = basis.partialPivLu().solve(homogeneous);
  Eigen::MatrixX3d points(columns * n, 3);
  Eigen::VectorXd weights(columns * n);
  for (int i = 0; i < columns; ++i) {
    for (int k = 0; k < n; ++k) {
      const double w = net(k, i * 4 + 3);
      if (!(w > 0.0)) {
        throw make_error("loft: the interpolated weight of control point (", i, ", ", k, ") is ", w,
                         "; sections with very different weights cannot be skinned");
      }
      points.row(i * n + k) = net.block<1, 3>(k, i * 4) / w;
      weights[i * n + k] = w;
    }
  }
  if (section_parameters != nullptr) {
    *section_parameters = parameters;
  }
  return NurbsSurface(compatible.front().knots(), knots_v, std::move(points), std::move(weights));
}

NurbsSurface split_spans(const NurbsSurface& surface, const Eigen::Vector2i& parts) {
  const NurbsSurface along_u =
      refine_knots(surface, SurfaceDirection::kU, split_knots(surface.knots_u(), parts.x()));
  return refine_knots(along_u, SurfaceDirection::kV, split_knots(along_u.knots_v(), parts.y()));
}

NurbsCurve split_spans(const NurbsCurve& curve, int parts) {
  return refine_knots(curve, split_knots(curve.knots(), parts));
}

}  // namespace dnurbs
