// Throughput of NURBS surface evaluation with first and second derivatives (S, S_u, S_v, S_uu,
// S_uv, S_vv) side by side with Open CASCADE's Geom_BSplineSurface::D2 on the same surface and the
// same random parameters, for degrees 2, 3, 5, rational and not. Writes DIR/evaluation.csv
// (`--out DIR`). See bench/evaluation/README.md.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/span_cached_surface_evaluator.h"

#ifdef DNURBS_HAVE_OCCT
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#endif

namespace {

using dnurbs::KnotVector;
using dnurbs::NurbsSurface;
using dnurbs::SurfaceDerivatives;

constexpr int kControlPointsPerDirection = 14;
constexpr int kEvaluations = 100000;
constexpr int kRepeats = 5;

/// The six quantities S, S_u, S_v, S_uu, S_uv, S_vv at one parameter pair.
using SecondOrderValues = std::array<Eigen::Vector3d, 6>;
/// Evaluates the six quantities at (u, v).
using Evaluator = std::function<void(double, double, SecondOrderValues&)>;

SecondOrderValues from_derivatives(const SurfaceDerivatives& d) {
  return {d(0, 0), d(1, 0), d(0, 1), d(2, 0), d(1, 1), d(0, 2)};
}

/// A wavy height field over a 14 x 14 control grid, clamped uniform knots, weights in [0.5, 2]
/// when rational.
NurbsSurface bench_surface(int degree, bool rational, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> height(-1.0, 1.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const int n = kControlPointsPerDirection;
  Eigen::MatrixX3d points(n * n, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n * n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      points.row(i * n + j) << i, j, height(generator);
      if (rational) {
        weights[i * n + j] = weight(generator);
      }
    }
  }
  return NurbsSurface(KnotVector::clamped_uniform(degree, n),
                      KnotVector::clamped_uniform(degree, n), std::move(points),
                      std::move(weights));
}

#ifdef DNURBS_HAVE_OCCT
/// The same surface as an OCCT Geom_BSplineSurface: poles (1-based, u index first), weights and
/// the distinct knots with their multiplicities.
Handle(Geom_BSplineSurface) occt_surface(const NurbsSurface& surface) {
  const int count_u = surface.control_point_count_u();
  const int count_v = surface.control_point_count_v();
  TColgp_Array2OfPnt poles(1, count_u, 1, count_v);
  TColStd_Array2OfReal weights(1, count_u, 1, count_v);
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      const int index = surface.control_point_index(i, j);
      const Eigen::RowVector3d p = surface.control_points().row(index);
      poles.SetValue(i + 1, j + 1, gp_Pnt(p.x(), p.y(), p.z()));
      weights.SetValue(i + 1, j + 1, surface.weights()[index]);
    }
  }
  const auto distinct = [](const KnotVector& knots) {
    std::vector<double> values = knots.knots();
    values.erase(std::unique(values.begin(), values.end()), values.end());
    TColStd_Array1OfReal occt_knots(1, static_cast<int>(values.size()));
    TColStd_Array1OfInteger multiplicities(1, static_cast<int>(values.size()));
    for (std::size_t k = 0; k < values.size(); ++k) {
      occt_knots.SetValue(static_cast<int>(k) + 1, values[k]);
      multiplicities.SetValue(static_cast<int>(k) + 1, knots.multiplicity(values[k]));
    }
    return std::pair{occt_knots, multiplicities};
  };
  const auto [knots_u, multiplicities_u] = distinct(surface.knots_u());
  const auto [knots_v, multiplicities_v] = distinct(surface.knots_v());
  return new Geom_BSplineSurface(poles, weights, knots_u, knots_v, multiplicities_u,
                                 multiplicities_v, surface.degree_u(), surface.degree_v());
}

void store(const gp_Pnt& p, const gp_Vec& du, const gp_Vec& dv, const gp_Vec& duu,
           const gp_Vec& dvv, const gp_Vec& duv, SecondOrderValues& values) {
  values = {Eigen::Vector3d(p.X(), p.Y(), p.Z()),       Eigen::Vector3d(du.X(), du.Y(), du.Z()),
            Eigen::Vector3d(dv.X(), dv.Y(), dv.Z()),    Eigen::Vector3d(duu.X(), duu.Y(), duu.Z()),
            Eigen::Vector3d(duv.X(), duv.Y(), duv.Z()), Eigen::Vector3d(dvv.X(), dvv.Y(), dvv.Z())};
}
#endif

/// A std::chrono clock on the CPU time of the calling thread: on a machine shared with other
/// jobs, time spent descheduled would otherwise count against whichever evaluator was running.
struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;
  static time_point now() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return time_point(std::chrono::seconds(now.tv_sec) + std::chrono::nanoseconds(now.tv_nsec));
  }
};

/// Best-of-kRepeats evaluations per second (thread CPU time) over all parameters. The evaluator (a
/// lambda, called directly so that no std::function dispatch is timed) writes into one reused
/// result whose sum feeds a checksum, so the work cannot be optimized away.
template <typename Evaluate>
double evaluations_per_second(const Evaluate& evaluate, const std::vector<double>& us,
                              const std::vector<double>& vs, double& checksum) {
  double best_seconds = 0.0;
  SecondOrderValues values;
  for (int repeat = 0; repeat < kRepeats; ++repeat) {
    const auto start = ThreadCpuClock::now();
    for (std::size_t i = 0; i < us.size(); ++i) {
      evaluate(us[i], vs[i], values);
      checksum += values[0].x() + values[3].y() + values[5].z();
    }
    const std::chrono::duration<double> elapsed = ThreadCpuClock::now() - start;
    if (repeat == 0 || elapsed.count() < best_seconds) {
      best_seconds = elapsed.count();
    }
  }
  return static_cast<double>(us.size()) / best_seconds;
}

/// Largest difference between two evaluators over the parameters: points relative to the
/// bounding-box diagonal of the control net, each derivative relative to its largest magnitude.
double max_difference(const Evaluator& evaluate, const Evaluator& reference,
                      const std::vector<double>& us, const std::vector<double>& vs,
                      double box_diagonal) {
  std::array<double, 6> difference{};
  std::array<double, 6> magnitude{};
  magnitude[0] = box_diagonal;
  SecondOrderValues values;
  SecondOrderValues expected;
  for (std::size_t i = 0; i < us.size(); ++i) {
    evaluate(us[i], vs[i], values);
    reference(us[i], vs[i], expected);
    for (std::size_t q = 0; q < values.size(); ++q) {
      difference[q] = std::max(difference[q], (values[q] - expected[q]).norm());
      if (q > 0) {
        magnitude[q] = std::max(magnitude[q], expected[q].norm());
      }
    }
  }
  double worst = 0.0;
  for (std::size_t q = 0; q < difference.size(); ++q) {
    worst = std::max(worst, difference[q] / magnitude[q]);
  }
  return worst;
}

struct Row {
  std::string evaluator;
  int degree = 0;
  bool rational = false;
  double evaluations_per_second = 0.0;
  std::optional<double> ratio_to_occt;
  std::optional<double> max_difference;
};

std::string optional_number(const std::optional<double>& value) {
  if (!value) {
    return "";
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", *value);
  return buffer;
}

int run(const std::filesystem::path& out) {
  std::vector<Row> rows;
  double checksum = 0.0;
  for (const int degree : {2, 3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsSurface surface = bench_surface(degree, rational, 100U + degree);
      const dnurbs::SpanCachedSurfaceEvaluator span_cached(surface);
      const Eigen::Vector3d extent = surface.control_points().colwise().maxCoeff() -
                                     surface.control_points().colwise().minCoeff();
      std::mt19937 generator(7);
      std::uniform_real_distribution<double> parameter(0.0, 1.0);
      std::vector<double> us(kEvaluations);
      std::vector<double> vs(kEvaluations);
      for (int i = 0; i < kEvaluations; ++i) {
        us[static_cast<std::size_t>(i)] = parameter(generator);
        vs[static_cast<std::size_t>(i)] = parameter(generator);
      }

      SurfaceDerivatives derivatives;
      const auto de_boor = [&](double u, double v, SecondOrderValues& values) {
        surface.derivatives(u, v, 2, derivatives);
        values = from_derivatives(derivatives);
      };
      const auto cached = [&](double u, double v, SecondOrderValues& values) {
        span_cached.derivatives(u, v, 2, derivatives);
        values = from_derivatives(derivatives);
      };
      std::optional<double> occt_rate;
      std::optional<Evaluator> occt_reference;
#ifdef DNURBS_HAVE_OCCT
      const Handle(Geom_BSplineSurface) occt = occt_surface(surface);
      const GeomAdaptor_Surface adaptor(occt);
      gp_Pnt p;
      gp_Vec du, dv, duu, dvv, duv;
      const auto occt_d2 = [&](double u, double v, SecondOrderValues& values) {
        occt->D2(u, v, p, du, dv, duu, dvv, duv);
        store(p, du, dv, duu, dvv, duv, values);
      };
      const auto occt_adaptor_d2 = [&](double u, double v, SecondOrderValues& values) {
        adaptor.D2(u, v, p, du, dv, duu, dvv, duv);
        store(p, du, dv, duu, dvv, duv, values);
      };
      occt_rate = evaluations_per_second(occt_d2, us, vs, checksum);
      occt_reference = occt_d2;
      rows.push_back({"occt_geom_bspline_surface_d2", degree, rational, *occt_rate, 1.0,
                      max_difference(occt_d2, de_boor, us, vs, extent.norm())});
      const double adaptor_rate = evaluations_per_second(occt_adaptor_d2, us, vs, checksum);
      rows.push_back({"occt_geom_adaptor_surface_d2", degree, rational, adaptor_rate,
                      adaptor_rate / *occt_rate,
                      max_difference(occt_adaptor_d2, de_boor, us, vs, extent.norm())});
#endif
      // Differences against OCCT when present, else against the de Boor evaluator.
      const auto add_dnurbs_row = [&](const char* name, const auto& evaluator, bool is_reference) {
        const double rate = evaluations_per_second(evaluator, us, vs, checksum);
        std::optional<double> difference;
        if (occt_reference) {
          difference = max_difference(evaluator, *occt_reference, us, vs, extent.norm());
        } else if (!is_reference) {
          difference = max_difference(evaluator, de_boor, us, vs, extent.norm());
        }
        std::optional<double> ratio;
        if (occt_rate) {
          ratio = rate / *occt_rate;
        }
        rows.push_back({name, degree, rational, rate, ratio, difference});
      };
      add_dnurbs_row("dnurbs_nurbs_surface", de_boor, true);
      add_dnurbs_row("dnurbs_span_cached", cached, false);
    }
  }

  std::filesystem::create_directories(out);
  std::ofstream csv(out / "evaluation.csv");
  if (!csv) {
    std::fprintf(stderr, "evaluation_bench: cannot write %s\n", (out / "evaluation.csv").c_str());
    return 1;
  }
  csv << "evaluator,degree,rational,evaluations_per_second,ratio_to_occt,max_difference\n";
  std::printf("%-30s %6s %8s %14s %8s %12s\n", "evaluator", "degree", "rational", "evals/s",
              "x occt", "max diff");
  for (const Row& row : rows) {
    csv << row.evaluator << ',' << row.degree << ',' << (row.rational ? 1 : 0) << ','
        << optional_number(row.evaluations_per_second) << ',' << optional_number(row.ratio_to_occt)
        << ',' << optional_number(row.max_difference) << '\n';
    std::printf("%-30s %6d %8d %14.4g %8s %12s\n", row.evaluator.c_str(), row.degree,
                row.rational ? 1 : 0, row.evaluations_per_second,
                optional_number(row.ratio_to_occt).c_str(),
                optional_number(row.max_difference).c_str());
  }
  std::printf("checksum %g\n", checksum);
  // The evaluators must agree to 1e-12 (relative, as max_difference measures it).
  constexpr double kAgreement = 1e-12;
  for (const Row& row : rows) {
    if (row.max_difference && !(*row.max_difference <= kAgreement)) {
      std::fprintf(stderr, "evaluation_bench: %s (degree %d) differs by %g > %g\n",
                   row.evaluator.c_str(), row.degree, *row.max_difference, kAgreement);
      return 1;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path out = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "usage: evaluation_bench [--out DIR]  (unknown argument '%s')\n",
                   argument.c_str());
      return 2;
    }
  }
  try {
    return run(out);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "evaluation_bench: %s\n", error.what());
    return 1;
  }
}
