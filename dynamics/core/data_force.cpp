#include "dnurbs/dynamics/core/data_force.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

void DataForceSettings::validate() const {
  if (!(stiffness >= 0.0) || !std::isfinite(stiffness)) {
    throw make_error("data force stiffness ", stiffness, " is not >= 0 and finite");
  }
  if (search_segments < 2 || search_segments > 4096) {
    throw make_error("data force search segments ", search_segments, " not in 2..4096");
  }
  if (refinement_steps < 0 || refinement_steps > 100) {
    throw make_error("data force refinement steps ", refinement_steps, " not in 0..100");
  }
}

namespace {

// The parameter box of one direction: [low, high], periodic or clamped.
struct Span {
  double low = 0.0;
  double high = 1.0;
  bool periodic = false;

  double fit(double x) const {
    if (!periodic) {
      return std::clamp(x, low, high);
    }
    const double width = high - low;
    return low + (x - low) - width * std::floor((x - low) / width);
  }
  // Grid sample i of `segments` cells (a periodic direction leaves out the repeated end).
  int samples(int segments) const { return periodic ? segments : segments + 1; }
  double sample(int i, int segments) const { return low + (high - low) * i / segments; }
};

class NearestPointSearch {
 public:
  NearestPointSearch(const Model& model, ConstVectorRef q, const DataForceSettings& settings)
      : model_(model), q_(q), settings_(settings) {
    const ParameterDomain domain = model.parameter_domain(q);
    u_ = {domain.u_min, domain.u_max, domain.periodic_u};
    surface_ = model.parametric_dimension() == 2;
    if (surface_) {
      v_ = {domain.v_min, domain.v_max, domain.periodic_v};
    } else {
      v_ = {0.0, 0.0, false};
    }
    const int segments = settings.search_segments;
    const int nu = u_.samples(segments);
    const int nv = surface_ ? v_.samples(segments) : 1;
    grid_parameters_.resize(static_cast<size_t>(nu) * nv);
    grid_positions_.resize(nu * nv, 3);
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const Eigen::Vector2d u(u_.sample(i, segments), surface_ ? v_.sample(j, segments) : v_.low);
        grid_parameters_[static_cast<size_t>(i) * nv + j] = u;
        grid_positions_.row(i * nv + j) = model.position(q, u).transpose();
      }
    }
  }

  NearestMaterialPoint find(const Eigen::Vector3d& point) const {
    Eigen::Index best = 0;
    (grid_positions_.rowwise() - point.transpose()).rowwise().squaredNorm().minCoeff(&best);
    NearestMaterialPoint nearest{grid_parameters_[static_cast<size_t>(best)],
                                 grid_positions_.row(best).transpose()};
    double distance = (nearest.position - point).squaredNorm();
    for (int step = 0; step < settings_.refinement_steps; ++step) {
      if (!refine(point, nearest, distance)) {
        break;
      }
    }
    return nearest;
  }

 private:
  // One Newton step on (1/2)|x(u) - z|^2, its gradient T^T r and Hessian T^T T + sum_i r_i
  // d^2 x_i / du^2 by central differences (Gauss-Newton's T^T T alone stalls where |r| is as
  // large as the radius of curvature: its step is then twice too long), halved until the
  // distance decreases; false when no step decreases it (converged to round-off). Where the
  // Hessian is not positive definite the Gauss-Newton matrix takes its place, with a small
  // Levenberg-Marquardt damping that keeps the step defined where a tangent vanishes (a pole).
  bool refine(const Eigen::Vector3d& point, NearestMaterialPoint& nearest, double& distance) const {
    const int dimension = surface_ ? 2 : 1;
    const Eigen::Vector2d u = nearest.parameter;
    const Eigen::Vector2d h(1e-5 * (u_.high - u_.low), surface_ ? 1e-5 * (v_.high - v_.low) : 0.0);
    const auto x = [&](double du, double dv) {
      return model_.position(q_, Eigen::Vector2d(u.x() + du * h.x(), u.y() + dv * h.y()));
    };
    const Eigen::Vector3d residual = nearest.position - point;
    Eigen::Matrix<double, 3, 2> tangents = Eigen::Matrix<double, 3, 2>::Zero();
    Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
    const Eigen::Vector3d plus_u = x(1, 0);
    const Eigen::Vector3d minus_u = x(-1, 0);
    tangents.col(0) = (plus_u - minus_u) / (2.0 * h.x());
    hessian(0, 0) = residual.dot(plus_u - 2.0 * nearest.position + minus_u) / (h.x() * h.x());
    if (dimension == 2) {
      const Eigen::Vector3d plus_v = x(0, 1);
      const Eigen::Vector3d minus_v = x(0, -1);
      tangents.col(1) = (plus_v - minus_v) / (2.0 * h.y());
      hessian(1, 1) = residual.dot(plus_v - 2.0 * nearest.position + minus_v) / (h.y() * h.y());
      hessian(0, 1) = hessian(1, 0) =
          residual.dot(x(1, 1) - x(1, -1) - x(-1, 1) + x(-1, -1)) / (4.0 * h.x() * h.y());
    }
    const Eigen::Matrix2d gauss_newton = tangents.transpose() * tangents;
    const double damping = 1e-12 * gauss_newton.trace();
    if (!(damping > 0.0)) {
      return false;  // x does not depend on u here: keep the answer so far
    }
    const Eigen::Vector2d gradient = tangents.transpose() * residual;
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    if (dimension == 2) {
      Eigen::Matrix2d matrix = gauss_newton + hessian;
      if (!(matrix.determinant() > 0.0 && matrix.trace() > 0.0)) {
        matrix = gauss_newton;
      }
      step = -(matrix + damping * Eigen::Matrix2d::Identity()).ldlt().solve(gradient);
    } else {
      const double curvature = gauss_newton(0, 0) + hessian(0, 0);
      step[0] = -gradient[0] / ((curvature > 0.0 ? curvature : gauss_newton(0, 0)) + damping);
    }
    // Converged when the step is at the round-off of the parameters. Equal distances are
    // accepted: near the answer |r|^2 changes below its own round-off (eps |r|^2) while the
    // Newton step still gains digits of u.
    if (std::abs(step.x()) <= 1e-15 * (u_.high - u_.low) &&
        std::abs(step.y()) <= 1e-15 * (v_.high - v_.low + 1.0)) {
      return false;
    }
    for (double scale = 1.0; scale > 1.0 / 16.0; scale *= 0.5) {
      const Eigen::Vector2d candidate(
          u_.fit(nearest.parameter.x() + scale * step.x()),
          surface_ ? v_.fit(nearest.parameter.y() + scale * step.y()) : nearest.parameter.y());
      const Eigen::Vector3d position = model_.position(q_, candidate);
      const double candidate_distance = (position - point).squaredNorm();
      if (candidate_distance <= distance) {
        nearest = {candidate, position};
        distance = candidate_distance;
        return true;
      }
    }
    return false;
  }

  const Model& model_;
  ConstVectorRef q_;
  const DataForceSettings& settings_;
  Span u_;
  Span v_;
  bool surface_ = false;
  std::vector<Eigen::Vector2d> grid_parameters_;
  Eigen::MatrixX3d grid_positions_;
};

void check_points(const Eigen::MatrixX3d& points, const char* what) {
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    if (!points.row(k).allFinite()) {
      throw make_error(what, " point ", k, " (", points(k, 0), ", ", points(k, 1), ", ",
                       points(k, 2), ") is not finite");
    }
  }
}

}  // namespace

std::vector<NearestMaterialPoint> nearest_material_points(const Model& model, ConstVectorRef q,
                                                          const Eigen::MatrixX3d& points,
                                                          const DataForceSettings& settings) {
  settings.validate();
  check_points(points, "nearest material point of data");
  const NearestPointSearch search(model, q, settings);
  std::vector<NearestMaterialPoint> nearest;
  nearest.reserve(static_cast<size_t>(points.rows()));
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    nearest.push_back(search.find(points.row(k).transpose()));
  }
  return nearest;
}

Force moving_data_force(PointsOfTime points, const DataForceSettings& settings) {
  settings.validate();
  if (!points) {
    throw make_error("data force has no point function");
  }
  return [points = std::move(points), settings](const Model& model, double t, ConstVectorRef q,
                                                ConstVectorRef /*qd*/, VectorRef generalized) {
    const Eigen::MatrixX3d z = points(t);
    check_points(z, "data force");
    const NearestPointSearch search(model, q, settings);
    for (Eigen::Index k = 0; k < z.rows(); ++k) {
      const Eigen::Vector3d point = z.row(k).transpose();
      const NearestMaterialPoint nearest = search.find(point);
      // Terzopoulos & Metaxas 1991: the spring force k (z - x(u)) at the nearest point.
      model.add_point_force(q, nearest.parameter, settings.stiffness * (point - nearest.position),
                            generalized);
    }
  };
}

Force data_force(const Eigen::MatrixX3d& points, const DataForceSettings& settings) {
  check_points(points, "data force");
  return moving_data_force([points](double) { return points; }, settings);
}

}  // namespace dnurbs
