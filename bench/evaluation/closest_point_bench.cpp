// Closest-point throughput (queries per second) on degree-3 curves and surfaces, rational and
// not, side by side with Open CASCADE's GeomAPI_ProjectPointOnCurve / GeomAPI_ProjectPointOnSurf
// on the same shapes and the same query points, with the number of global misses of each
// against a brute-force reference. Writes DIR/closest_point.csv (`--out DIR`). See
// bench/evaluation/README.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "dnurbs/nurbs/closest_point.h"
#include "tests/nurbs/brute_force_projection.h"

#ifdef DNURBS_HAVE_OCCT
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#endif

namespace {

using dnurbs::KnotVector;
using dnurbs::NurbsCurve;
using dnurbs::NurbsSurface;

constexpr int kDegree = 3;
constexpr int kCurveQueries = 3000;
constexpr int kSurfaceQueries = 1000;
constexpr int kRepeats = 3;
// A result farther than the reference by more than this (relative to the shape's size) is a
// global miss: the reference is exact to ~1e-15, so anything above is a wrong local minimum.
constexpr double kMissTolerance = 1e-9;

/// CPU time of the calling thread in seconds: time descheduled on a shared machine is not
/// counted against whichever method was running.
double thread_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// A wavy space curve: 24 control points along x with y, z in [-1, 1], clamped uniform knots,
/// weights in [0.5, 2] when rational.
NurbsCurve bench_curve(bool rational, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> offset(-1.0, 1.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const int n = 24;
  Eigen::MatrixX3d points(n, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; ++i) {
    points.row(i) << 0.5 * i, offset(generator), offset(generator);
    weights[i] = rational ? weight(generator) : 1.0;
  }
  return {KnotVector::clamped_uniform(kDegree, n), points, weights};
}

/// A wavy height field over a 14 x 14 control grid (as evaluation_bench), clamped uniform knots.
NurbsSurface bench_surface(bool rational, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> height(-1.0, 1.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const int n = 14;
  const Eigen::Index count = static_cast<Eigen::Index>(n) * n;
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(count);
  for (int i = 0; i < count; ++i) {
    const int row = i / n;
    points.row(i) << row, i % n, height(generator);
    weights[i] = rational ? weight(generator) : 1.0;
  }
  return {KnotVector::clamped_uniform(kDegree, n), KnotVector::clamped_uniform(kDegree, n), points,
          weights};
}

/// Query points: a third on the shape, a third near it (a random offset of length 10^-3..10^-0.5
/// times the size) and a third anywhere in its bounding box grown by half its size.
template <typename PointAt>
std::vector<Eigen::Vector3d> bench_queries(const Eigen::MatrixX3d& control_points, int count,
                                           const PointAt& point_at, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d low = control_points.colwise().minCoeff();
  const Eigen::Vector3d high = control_points.colwise().maxCoeff();
  const double size = (high - low).norm();
  std::vector<Eigen::Vector3d> queries;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d on = point_at(unit(generator), unit(generator));
    const Eigen::Vector3d direction =
        Eigen::Vector3d(unit(generator) - 0.5, unit(generator) - 0.5, unit(generator) - 0.5)
            .normalized();
    const Eigen::Vector3d anywhere =
        low - 0.25 * (high - low) +
        1.5 * (high - low)
                  .cwiseProduct(Eigen::Vector3d(unit(generator), unit(generator), unit(generator)));
    const double length = size * std::pow(10.0, -3.0 + 2.5 * unit(generator));
    queries.push_back(
        i % 3 == 0 ? on : (i % 3 == 1 ? Eigen::Vector3d(on + length * direction) : anywhere));
  }
  return queries;
}

#ifdef DNURBS_HAVE_OCCT
/// The distinct knots and multiplicities of a knot vector, 1-based for OCCT.
std::pair<TColStd_Array1OfReal, TColStd_Array1OfInteger> occt_knots(const KnotVector& knots) {
  std::vector<double> values = knots.knots();
  values.erase(std::unique(values.begin(), values.end()), values.end());
  const int count = static_cast<int>(values.size());
  TColStd_Array1OfReal distinct(1, count);
  TColStd_Array1OfInteger multiplicities(1, count);
  for (int k = 0; k < count; ++k) {
    distinct.SetValue(k + 1, values[static_cast<std::size_t>(k)]);
    multiplicities.SetValue(k + 1, knots.multiplicity(values[static_cast<std::size_t>(k)]));
  }
  return {distinct, multiplicities};
}

gp_Pnt to_occt(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

Handle(Geom_BSplineCurve) occt_curve(const NurbsCurve& curve) {
  const int n = curve.control_point_count();
  TColgp_Array1OfPnt poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    poles.SetValue(i + 1, to_occt(curve.control_points().row(i).transpose()));
    weights.SetValue(i + 1, curve.weights()[i]);
  }
  const auto [knots, multiplicities] = occt_knots(curve.knots());
  return new Geom_BSplineCurve(poles, weights, knots, multiplicities, curve.degree());
}

Handle(Geom_BSplineSurface) occt_surface(const NurbsSurface& surface) {
  const int count_u = surface.control_point_count_u();
  const int count_v = surface.control_point_count_v();
  TColgp_Array2OfPnt poles(1, count_u, 1, count_v);
  TColStd_Array2OfReal weights(1, count_u, 1, count_v);
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      const int index = surface.control_point_index(i, j);
      poles.SetValue(i + 1, j + 1, to_occt(surface.control_points().row(index).transpose()));
      weights.SetValue(i + 1, j + 1, surface.weights()[index]);
    }
  }
  const auto [knots_u, multiplicities_u] = occt_knots(surface.knots_u());
  const auto [knots_v, multiplicities_v] = occt_knots(surface.knots_v());
  return new Geom_BSplineSurface(poles, weights, knots_u, knots_v, multiplicities_u,
                                 multiplicities_v, surface.degree_u(), surface.degree_v());
}
#endif

/// One method's result on one shape.
struct Row {
  std::string shape;
  bool rational = false;
  std::string method;
  double queries_per_second = 0.0;
  std::optional<double> ratio_to_occt;
  int misses = 0;
  int queries = 0;
};

/// Best-of-kRepeats queries per second of `distance_of` (a lambda returning the distance it
/// finds, or a negative value when it finds nothing) over the queries, and its global misses
/// against the reference distances.
template <typename DistanceOf>
Row measure(const std::vector<Eigen::Vector3d>& queries, const std::vector<double>& reference,
            double size, const DistanceOf& distance_of) {
  Row row;
  row.queries = static_cast<int>(queries.size());
  std::vector<double> found(queries.size());
  double best = 0.0;
  for (int repeat = 0; repeat < kRepeats; ++repeat) {
    const double start = thread_seconds();
    for (std::size_t i = 0; i < queries.size(); ++i) {
      found[i] = distance_of(queries[i]);
    }
    const double elapsed = thread_seconds() - start;
    best = repeat == 0 ? elapsed : std::min(best, elapsed);
  }
  row.queries_per_second = static_cast<double>(queries.size()) / best;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    row.misses += found[i] < 0.0 || found[i] > reference[i] + kMissTolerance * size ? 1 : 0;
  }
  return row;
}

std::string number(const std::optional<double>& value) {
  if (!value) {
    return "";
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", *value);
  return buffer;
}

void add_rows(std::vector<Row>& rows, std::vector<Row> shape_rows, const std::string& shape,
              bool rational) {
  std::optional<double> occt_rate;
  for (const Row& row : shape_rows) {
    if (row.method.rfind("occt", 0) == 0) {
      occt_rate = row.queries_per_second;
    }
  }
  for (Row& row : shape_rows) {
    row.shape = shape;
    row.rational = rational;
    if (occt_rate) {
      row.ratio_to_occt = row.queries_per_second / *occt_rate;
    }
    rows.push_back(row);
  }
}

std::vector<Row> curve_rows(bool rational) {
  const NurbsCurve curve = bench_curve(rational, 300U + (rational ? 1U : 0U));
  const double start = curve.knots().domain_start();
  const double end = curve.knots().domain_end();
  const std::vector<Eigen::Vector3d> queries = bench_queries(
      curve.control_points(), kCurveQueries,
      [&](double a, double) { return curve.point(start + a * (end - start)); }, 11U);
  const double size =
      (curve.control_points().colwise().maxCoeff() - curve.control_points().colwise().minCoeff())
          .norm();
  const dnurbs::testing::CurveSamples samples = dnurbs::testing::sample_curve(curve, 64);
  std::vector<double> reference;
  reference.reserve(queries.size());
  for (const Eigen::Vector3d& query : queries) {
    reference.push_back(dnurbs::testing::brute_force_distance(curve, samples, query));
  }
  std::vector<Row> rows;
#ifdef DNURBS_HAVE_OCCT
  const Handle(Geom_BSplineCurve) occt = occt_curve(curve);
  GeomAPI_ProjectPointOnCurve projection;
  projection.Init(occt, start, end);
  rows.push_back(measure(queries, reference, size, [&](const Eigen::Vector3d& query) {
    projection.Perform(to_occt(query));
    return projection.NbPoints() > 0 ? projection.LowerDistance() : -1.0;
  }));
  rows.back().method = "occt_geomapi_project_point_on_curve";
#endif
  const dnurbs::CurveProjector projector(curve);
  rows.push_back(measure(queries, reference, size, [&](const Eigen::Vector3d& query) {
    return projector.closest_point(query).distance;
  }));
  rows.back().method = "dnurbs_curve_projector";
  return rows;
}

std::vector<Row> surface_rows(bool rational) {
  const NurbsSurface surface = bench_surface(rational, 400U + (rational ? 1U : 0U));
  const std::vector<Eigen::Vector3d> queries = bench_queries(
      surface.control_points(), kSurfaceQueries,
      [&](double a, double b) { return surface.point(a, b); }, 12U);
  const double size = (surface.control_points().colwise().maxCoeff() -
                       surface.control_points().colwise().minCoeff())
                          .norm();
  const dnurbs::testing::SurfaceSamples samples = dnurbs::testing::sample_surface(surface, 12);
  std::vector<double> reference;
  reference.reserve(queries.size());
  for (const Eigen::Vector3d& query : queries) {
    reference.push_back(dnurbs::testing::brute_force_distance(surface, samples, query));
  }
  std::vector<Row> rows;
#ifdef DNURBS_HAVE_OCCT
  const Handle(Geom_BSplineSurface) occt = occt_surface(surface);
  GeomAPI_ProjectPointOnSurf projection;
  projection.Init(occt, 0.0, 1.0, 0.0, 1.0);
  rows.push_back(measure(queries, reference, size, [&](const Eigen::Vector3d& query) {
    projection.Perform(to_occt(query));
    return projection.NbPoints() > 0 ? projection.LowerDistance() : -1.0;
  }));
  rows.back().method = "occt_geomapi_project_point_on_surf";
#endif
  const dnurbs::SurfaceProjector projector(surface);
  rows.push_back(measure(queries, reference, size, [&](const Eigen::Vector3d& query) {
    return projector.closest_point(query).distance;
  }));
  rows.back().method = "dnurbs_surface_projector";
  return rows;
}

int run(const std::filesystem::path& out) {
  std::vector<Row> rows;
  for (const bool rational : {false, true}) {
    add_rows(rows, curve_rows(rational), "curve", rational);
    add_rows(rows, surface_rows(rational), "surface", rational);
  }
  std::filesystem::create_directories(out);
  std::ofstream csv(out / "closest_point.csv");
  if (!csv) {
    std::fprintf(stderr, "closest_point_bench: cannot write %s\n",
                 (out / "closest_point.csv").c_str());
    return 1;
  }
  csv << "shape,degree,rational,method,queries_per_second,ratio_to_occt,global_misses,queries\n";
  std::printf("%-8s %8s %-38s %12s %8s %8s\n", "shape", "rational", "method", "queries/s", "x occt",
              "misses");
  int status = 0;
  for (const Row& row : rows) {
    csv << row.shape << ',' << kDegree << ',' << (row.rational ? 1 : 0) << ',' << row.method << ','
        << number(row.queries_per_second) << ',' << number(row.ratio_to_occt) << ',' << row.misses
        << ',' << row.queries << '\n';
    std::printf("%-8s %8d %-38s %12.4g %8s %5d/%d\n", row.shape.c_str(), row.rational ? 1 : 0,
                row.method.c_str(), row.queries_per_second, number(row.ratio_to_occt).c_str(),
                row.misses, row.queries);
    // dnurbs must find the global minimum of every query.
    if (row.method.rfind("dnurbs", 0) == 0 && row.misses > 0) {
      std::fprintf(stderr, "closest_point_bench: %s missed %d global minima\n", row.method.c_str(),
                   row.misses);
      status = 1;
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path out = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "usage: closest_point_bench [--out DIR]  (unknown argument '%s')\n",
                   argument.c_str());
      return 2;
    }
  }
  try {
    return run(out);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "closest_point_bench: %s\n", error.what());
    return 1;
  }
}
