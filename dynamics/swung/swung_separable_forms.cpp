#include "dnurbs/dynamics/swung/swung_separable_forms.h"

namespace dnurbs {
namespace {

// Derivative orders (k in u, l in v) of the quantities S, S_u, S_v, S_uu, S_uv, S_vv.
constexpr std::array<int, 6> kOrderU = {0, 1, 0, 2, 1, 0};
constexpr std::array<int, 6> kOrderV = {0, 0, 1, 0, 1, 2};

// Coordinate kinds: the two coordinates of a profile point (x, z) and of a trajectory point.
enum Kind { kProfileX = 0, kProfileZ = 1, kTrajectoryX = 2, kTrajectoryY = 3 };

// Gram matrices integral R^(d) R^(d)^T of one curve, d = 0..2, over its Gauss points (products
// formed as (w R_a) R_b for both orders of a, b: exactly symmetric).
std::array<Eigen::MatrixXd, 3> gram_matrices(const std::vector<PlanarCurveSample>& samples,
                                             const std::vector<double>& weights, int count) {
  std::array<Eigen::MatrixXd, 3> gram;
  for (Eigen::MatrixXd& g : gram) {
    g = Eigen::MatrixXd::Zero(count, count);
  }
  for (size_t i = 0; i < samples.size(); ++i) {
    const PlanarCurveSample& s = samples[i];
    for (int d = 0; d < 3; ++d) {
      for (int a = 0; a <= s.degree; ++a) {
        for (int b = 0; b <= s.degree; ++b) {
          gram[static_cast<size_t>(d)](s.control_point[static_cast<size_t>(a)],
                                       s.control_point[static_cast<size_t>(b)]) +=
              weights[i] * (s.rational(d, a) * s.rational(d, b));
        }
      }
    }
  }
  return gram;
}

}  // namespace

SwungSeparableForms::SwungSeparableForms(const SwungQuadrature& quadrature,
                                         const SwungLayout& layout, double alpha,
                                         const std::vector<PlanarCurveSample>& profile,
                                         const std::vector<PlanarCurveSample>& trajectory,
                                         const double* material)
    : layout_(layout), alpha_(alpha), mu_(material[0]), gamma_(material[1]) {
  std::vector<double> weights_u(profile.size());
  std::vector<double> weights_v(trajectory.size());
  for (size_t i = 0; i < weights_u.size(); ++i) {
    weights_u[i] = quadrature.profile_weight(static_cast<int>(i));
  }
  for (size_t j = 0; j < weights_v.size(); ++j) {
    weights_v[j] = quadrature.trajectory_weight(static_cast<int>(j));
    length_v_ += weights_v[j];
  }
  profile_gram_ = gram_matrices(profile, weights_u, layout.profile_count);
  trajectory_gram_ = gram_matrices(trajectory, weights_v, layout.trajectory_count);
  for (int q = 1; q < 6; ++q) {
    k_[static_cast<size_t>(q)] = material[1 + q];
  }
  rest_ = split(Eigen::VectorXd::Zero(layout.coordinate_count()));
}

void SwungSeparableForms::set_rest(const Eigen::Ref<const Eigen::VectorXd>& q_rest) {
  rest_ = split(q_rest);
  has_rest_ = true;
}

SwungSeparableForms::Split SwungSeparableForms::change(const Split& s) const {
  return {s.profile_x - rest_.profile_x, s.profile_z - rest_.profile_z,
          s.trajectory_x - rest_.trajectory_x, s.trajectory_y - rest_.trajectory_y};
}

SwungSeparableForms::Split SwungSeparableForms::split(
    const Eigen::Ref<const Eigen::VectorXd>& q) const {
  Split s;
  s.profile_x.resize(layout_.profile_count);
  s.profile_z.resize(layout_.profile_count);
  s.trajectory_x.resize(layout_.trajectory_count);
  s.trajectory_y.resize(layout_.trajectory_count);
  for (int i = 0; i < layout_.profile_count; ++i) {
    s.profile_x[i] = q[layout_.profile_offset(i)];
    s.profile_z[i] = q[layout_.profile_offset(i) + 1];
  }
  for (int j = 0; j < layout_.trajectory_count; ++j) {
    s.trajectory_x[j] = q[layout_.trajectory_offset(j)];
    s.trajectory_y[j] = q[layout_.trajectory_offset(j) + 1];
  }
  return s;
}

void SwungSeparableForms::add_block(int row_kind, int column_kind, const Eigen::MatrixXd& block,
                                    Eigen::MatrixXd& matrix) const {
  const auto index = [this](int kind, Eigen::Index i) {
    const int point = static_cast<int>(i);
    return kind < kTrajectoryX ? layout_.profile_offset(point) + kind
                               : layout_.trajectory_offset(point) + kind - kTrajectoryX;
  };
  for (Eigen::Index c = 0; c < block.cols(); ++c) {
    for (Eigen::Index r = 0; r < block.rows(); ++r) {
      matrix(index(row_kind, r), index(column_kind, c)) += block(r, c);
    }
  }
}

void SwungSeparableForms::add_profile_trajectory_coupling(const Eigen::MatrixXd& with_x,
                                                          const Eigen::MatrixXd& with_y,
                                                          Eigen::MatrixXd& matrix) const {
  add_block(kProfileX, kTrajectoryX, with_x, matrix);
  add_block(kTrajectoryX, kProfileX, with_x.transpose(), matrix);
  add_block(kProfileX, kTrajectoryY, with_y, matrix);
  add_block(kTrajectoryY, kProfileX, with_y.transpose(), matrix);
}

void SwungSeparableForms::add_vector(int kind, const Eigen::VectorXd& values,
                                     Eigen::Ref<Eigen::VectorXd>& vector) const {
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const int point = static_cast<int>(i);
    vector[kind < kTrajectoryX ? layout_.profile_offset(point) + kind
                               : layout_.trajectory_offset(point) + kind - kTrajectoryX] +=
        values[i];
  }
}

void SwungSeparableForms::matrices(const Eigen::Ref<const Eigen::VectorXd>& q,
                                   bool geometric_stiffness, Eigen::MatrixXd& mass,
                                   Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness) const {
  const Split s = split(q);
  const double a2 = alpha_ * alpha_;
  // M and D (Terzopoulos, eq. 1.25): the same form scaled by mu and by gamma.
  const Eigen::MatrixXd& a0 = profile_gram_[0];
  const Eigen::MatrixXd& b0 = trajectory_gram_[0];
  const double f0 = s.profile_x.dot(a0 * s.profile_x);
  const double g0 =
      s.trajectory_x.dot(b0 * s.trajectory_x) + s.trajectory_y.dot(b0 * s.trajectory_y);
  const Eigen::VectorXd a0x = a0 * s.profile_x;
  const Eigen::MatrixXd cross_x = a0x * (b0 * s.trajectory_x).transpose();
  const Eigen::MatrixXd cross_y = a0x * (b0 * s.trajectory_y).transpose();
  for (auto [matrix, density] : {std::pair{&mass, mu_}, std::pair{&damping, gamma_}}) {
    if (density == 0.0 && matrix == &damping) {
      continue;
    }
    const double c = density * a2;
    add_block(kProfileX, kProfileX, c * g0 * a0, *matrix);
    add_block(kProfileZ, kProfileZ, density * length_v_ * a0, *matrix);
    add_block(kTrajectoryX, kTrajectoryX, c * f0 * b0, *matrix);
    add_block(kTrajectoryY, kTrajectoryY, c * f0 * b0, *matrix);
    const Eigen::MatrixXd scaled_x = c * cross_x;
    const Eigen::MatrixXd scaled_y = c * cross_y;
    add_profile_trajectory_coupling(scaled_x, scaled_y, *matrix);
  }
  // Tangent stiffness d^2 E / dq^2 (Terzopoulos, eq. 1.20 integrated in closed form over the
  // product of the curves): the cross blocks carry factor 2, of which 1 is the Gauss-Newton part.
  const double cross_factor = geometric_stiffness ? 2.0 : 1.0;
  for (int quantity = 1; quantity < 6; ++quantity) {
    const double k = k_[static_cast<size_t>(quantity)];
    if (k == 0.0) {
      continue;
    }
    const Eigen::MatrixXd& ak = profile_gram_[static_cast<size_t>(kOrderU[quantity])];
    const Eigen::MatrixXd& bl = trajectory_gram_[static_cast<size_t>(kOrderV[quantity])];
    const double fk = s.profile_x.dot(ak * s.profile_x);
    const double gl =
        s.trajectory_x.dot(bl * s.trajectory_x) + s.trajectory_y.dot(bl * s.trajectory_y);
    add_block(kProfileX, kProfileX, k * a2 * gl * ak, stiffness);
    if (kOrderV[quantity] == 0) {
      add_block(kProfileZ, kProfileZ, k * length_v_ * ak, stiffness);
    }
    add_block(kTrajectoryX, kTrajectoryX, k * a2 * fk * bl, stiffness);
    add_block(kTrajectoryY, kTrajectoryY, k * a2 * fk * bl, stiffness);
    const Eigen::VectorXd akx = (cross_factor * k * a2) * (ak * s.profile_x);
    Eigen::MatrixXd block_x = akx * (bl * s.trajectory_x).transpose();
    Eigen::MatrixXd block_y = akx * (bl * s.trajectory_y).transpose();
    if (geometric_stiffness && has_rest_) {
      // The exact tangent's second-derivative part weighs S^Q - S^Q(q_r) (file comment)
      const Eigen::VectorXd akx_rest = (k * a2) * (ak * rest_.profile_x);
      block_x -= akx_rest * (bl * rest_.trajectory_x).transpose();
      block_y -= akx_rest * (bl * rest_.trajectory_y).transpose();
    }
    add_profile_trajectory_coupling(block_x, block_y, stiffness);
  }
}

double SwungSeparableForms::energy(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  // E from the change d = q - q_r, term by term a product with it (file comment).
  const Split s = split(q);
  const Split d = change(s);
  double energy = 0.0;
  for (int quantity = 1; quantity < 6; ++quantity) {
    const double k = k_[static_cast<size_t>(quantity)];
    if (k == 0.0) {
      continue;
    }
    const Eigen::MatrixXd& ak = profile_gram_[static_cast<size_t>(kOrderU[quantity])];
    const Eigen::MatrixXd& bl = trajectory_gram_[static_cast<size_t>(kOrderV[quantity])];
    const Eigen::VectorXd ak_rest = ak * rest_.profile_x;
    const Eigen::VectorXd bl_change_x = bl * d.trajectory_x;
    const Eigen::VectorXd bl_change_y = bl * d.trajectory_y;
    const double gl =
        s.trajectory_x.dot(bl * s.trajectory_x) + s.trajectory_y.dot(bl * s.trajectory_y);
    const double gl_mixed = s.trajectory_x.dot(bl_change_x) + s.trajectory_y.dot(bl_change_y);
    const double gl_change = d.trajectory_x.dot(bl_change_x) + d.trajectory_y.dot(bl_change_y);
    energy += 0.5 * k * alpha_ * alpha_ *
              (d.profile_x.dot(ak * d.profile_x) * gl + 2.0 * d.profile_x.dot(ak_rest) * gl_mixed +
               rest_.profile_x.dot(ak_rest) * gl_change);
    if (kOrderV[quantity] == 0) {
      energy += 0.5 * k * length_v_ * d.profile_z.dot(ak * d.profile_z);
    }
  }
  return energy;
}

void SwungSeparableForms::add_internal_force(const Eigen::Ref<const Eigen::VectorXd>& q,
                                             Eigen::Ref<Eigen::VectorXd> force) const {
  // -dE/dq of the energy above, every term a product with the change d = q - q_r.
  const Split s = split(q);
  const Split d = change(s);
  for (int quantity = 1; quantity < 6; ++quantity) {
    const double k = k_[static_cast<size_t>(quantity)];
    if (k == 0.0) {
      continue;
    }
    const Eigen::MatrixXd& ak = profile_gram_[static_cast<size_t>(kOrderU[quantity])];
    const Eigen::MatrixXd& bl = trajectory_gram_[static_cast<size_t>(kOrderV[quantity])];
    const Eigen::VectorXd akx = ak * s.profile_x;
    const Eigen::VectorXd ak_change = ak * d.profile_x;
    const Eigen::VectorXd ak_rest = ak * rest_.profile_x;
    const Eigen::VectorXd blx = bl * s.trajectory_x;
    const Eigen::VectorXd bly = bl * s.trajectory_y;
    const Eigen::VectorXd bl_change_x = bl * d.trajectory_x;
    const Eigen::VectorXd bl_change_y = bl * d.trajectory_y;
    const double gl = s.trajectory_x.dot(blx) + s.trajectory_y.dot(bly);
    const double gl_mixed = s.trajectory_x.dot(bl_change_x) + s.trajectory_y.dot(bl_change_y);
    const double c = -k * alpha_ * alpha_;
    add_vector(kProfileX, c * (gl * ak_change + gl_mixed * ak_rest), force);
    const double change_x = d.profile_x.dot(akx);
    const double rest_x = rest_.profile_x.dot(akx);
    add_vector(kTrajectoryX, c * (change_x * blx + rest_x * bl_change_x), force);
    add_vector(kTrajectoryY, c * (change_x * bly + rest_x * bl_change_y), force);
    if (kOrderV[quantity] == 0) {
      add_vector(kProfileZ, -k * length_v_ * (ak * d.profile_z), force);
    }
  }
}

void SwungSeparableForms::add_inertial_force(const Eigen::Ref<const Eigen::VectorXd>& q,
                                             const Eigen::Ref<const Eigen::VectorXd>& qd,
                                             Eigen::Ref<Eigen::VectorXd> force) const {
  // g = -integral mu J^T (Jdot qd) with Jdot qd = (2 alpha f' t', 0) (rates along qd).
  const Split s = split(q);
  const Split r = split(qd);
  const Eigen::MatrixXd& a0 = profile_gram_[0];
  const Eigen::MatrixXd& b0 = trajectory_gram_[0];
  const Eigen::VectorXd a0_rate = a0 * r.profile_x;
  const Eigen::VectorXd b0_rate_x = b0 * r.trajectory_x;
  const Eigen::VectorXd b0_rate_y = b0 * r.trajectory_y;
  const double c = -2.0 * mu_ * alpha_ * alpha_;
  add_vector(kProfileX,
             c * (s.trajectory_x.dot(b0_rate_x) + s.trajectory_y.dot(b0_rate_y)) * a0_rate, force);
  const double profile_rate = s.profile_x.dot(a0_rate);
  add_vector(kTrajectoryX, c * profile_rate * b0_rate_x, force);
  add_vector(kTrajectoryY, c * profile_rate * b0_rate_y, force);
}

}  // namespace dnurbs
