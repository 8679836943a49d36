// TargetTrajectory::keyframes with each Interpolation: the natural cubic spline's overshoot on
// the keyframes of examples/scenes/swung_clay.json against its closed form, the monotone
// piecewise cubic of Fritsch & Carlson 1980 (bracketed by its keyframes, exact on linear data,
// C1), and the velocities and accelerations of every kind against differences of the position.

#include "dnurbs/constraints/target_trajectory.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

// swung_clay's point force: -3 for one second, released to 0 in 0.05 s (in x).
TargetTrajectory swung_clay_push(Interpolation interpolation) {
  return TargetTrajectory::keyframes(
      {0.0, 1.0, 1.05},
      {Eigen::Vector3d(-3, 0, 0), Eigen::Vector3d(-3, 0, 0), Eigen::Vector3d::Zero()},
      interpolation);
}

TEST(TargetTrajectoryKeyframes, CubicOvershootsSwungClayPushAsItsClosedFormSays) {
  // Natural spline moments: M0 = M2 = 0, 2 (h0 + h1) M1 = 6 (60 - 0), M1 = 360 / 2.1. On [0, 1]
  // (h0 = 1, value -3 at both ends) S(t) = -3 + (t^3 - t) M1 / 6, least at t = 1 / sqrt(3):
  // -3 - (2 / (3 sqrt 3)) M1 / 6 = -3 - 400 / (21 sqrt 3) = -13.9970.
  const TargetTrajectory cubic = swung_clay_push(Interpolation::kCubic);
  const double peak_time = 1.0 / std::sqrt(3.0);
  const double peak = -3.0 - 400.0 / (21.0 * std::sqrt(3.0));
  EXPECT_NEAR(cubic.position(peak_time).x(), peak, 1e-12);
  EXPECT_NEAR(peak, -13.997, 1e-3);
  EXPECT_NEAR(cubic.velocity(peak_time).x(), 0.0, 1e-12);
  double least = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    least = std::min(least, cubic.position(1.05 * k / 10000.0).x());
  }
  EXPECT_GE(least, peak - 1e-12);
  EXPECT_LT(least, peak + 1e-6);  // the sample nearest 1 / sqrt(3) is within 6e-5 of it
}

TEST(TargetTrajectoryKeyframes, MonotoneHoldsSwungClayPushAtMinusThreeThenReleases) {
  const TargetTrajectory monotone = swung_clay_push(Interpolation::kMonotone);
  for (int k = 0; k <= 10000; ++k) {
    const double t = 1.1 * k / 10000.0;
    const double x = monotone.position(t).x();
    if (t <= 1.0) {
      EXPECT_EQ(x, -3.0) << "t = " << t;  // flat segment: both slopes 0, exactly the keyframes
    }
    EXPECT_GE(x, -3.0) << "t = " << t;
    EXPECT_LE(x, 0.0) << "t = " << t;
  }
  // The release rises monotonically: slopes 0 at t = 1 and, from the end formula,
  // ((2 * 0.05 + 1) * 60 - 0.05 * 0) / 1.05 = 62.857 at t = 1.05.
  EXPECT_NEAR(monotone.velocity(1.05 - 1e-12).x(), 1.1 * 60.0 / 1.05, 1e-6);
  EXPECT_EQ(monotone.velocity(1.0).x(), 0.0);
}

TEST(TargetTrajectoryKeyframes, MonotoneReproducesLinearAndConstantDataExactly) {
  // Uneven times; x and y linear in t with exactly representable secants, z constant.
  const std::vector<double> times = {0.0, 0.5, 1.5, 2.0, 3.25};
  const auto line = [](double t) { return Eigen::Vector3d(0.5 * t - 0.25, -0.25 * t + 0.5, 0.75); };
  std::vector<Eigen::Vector3d> points;
  points.reserve(times.size());
  for (double t : times) {
    points.push_back(line(t));
  }
  const TargetTrajectory monotone =
      TargetTrajectory::keyframes(times, points, Interpolation::kMonotone);
  for (int k = 0; k <= 10000; ++k) {
    const double t = 3.25 * k / 10000.0;
    EXPECT_LE((monotone.position(t) - line(t)).cwiseAbs().maxCoeff(), 1e-15) << "t = " << t;
    if (t > 0.0 && t < 3.25) {
      EXPECT_EQ(monotone.velocity(t), Eigen::Vector3d(0.5, -0.25, 0.0)) << "t = " << t;
      EXPECT_EQ(monotone.acceleration(t), Eigen::Vector3d::Zero()) << "t = " << t;
    }
  }
}

// Keyframes with random gaps in [0.05, 2]; x rises (a third of the steps flat), y falls and z
// goes up and down.
void random_keyframes(unsigned seed, std::vector<double>& times,
                      std::vector<Eigen::Vector3d>& points) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> gap(0.05, 2.0);
  std::uniform_real_distribution<double> step(0.0, 3.0);
  std::uniform_real_distribution<double> any(-2.0, 2.0);
  times = {0.0};
  points = {Eigen::Vector3d::Zero()};
  for (int i = 1; i < 20; ++i) {
    const double rise = step(random);
    times.push_back(times.back() + gap(random));
    points.push_back(points.back() +
                     Eigen::Vector3d(rise < 1.0 ? 0.0 : rise, -step(random), any(random)));
  }
}

TEST(TargetTrajectoryKeyframes, MonotoneNeverLeavesTheKeyframeBracketOnRandomData) {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> points;
  random_keyframes(7, times, points);
  const TargetTrajectory monotone =
      TargetTrajectory::keyframes(times, points, Interpolation::kMonotone);
  const TargetTrajectory cubic = TargetTrajectory::keyframes(times, points, Interpolation::kCubic);
  int cubic_outside = 0;
  const double scale = 1e-14 * 60.0;  // round-off of values up to 60
  for (int k = 0; k < 10000; ++k) {
    const double t = times.back() * (k + 0.5) / 10000.0;
    const auto i =
        static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const Eigen::Vector3d low = points[i].cwiseMin(points[i + 1]);
    const Eigen::Vector3d high = points[i].cwiseMax(points[i + 1]);
    const Eigen::Vector3d x = monotone.position(t);
    EXPECT_TRUE((x.array() >= low.array() - scale).all() &&
                (x.array() <= high.array() + scale).all())
        << "t = " << t << ": " << x.transpose() << " outside [" << low.transpose() << "], ["
        << high.transpose() << "]";
    const Eigen::Vector3d y = cubic.position(t);
    cubic_outside +=
        (y.array() < low.array() - scale).any() || (y.array() > high.array() + scale).any();
  }
  // The same samples of the natural spline do leave the bracket (the check can fail)
  EXPECT_GT(cubic_outside, 100);
}

TEST(TargetTrajectoryKeyframes, MonotoneIsC1AtTheKeyframesAndCubicIsC2) {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> points;
  random_keyframes(11, times, points);
  const TargetTrajectory monotone =
      TargetTrajectory::keyframes(times, points, Interpolation::kMonotone);
  const TargetTrajectory cubic = TargetTrajectory::keyframes(times, points, Interpolation::kCubic);
  double monotone_jump = 0.0;
  for (size_t i = 1; i + 1 < times.size(); ++i) {
    // Just left of the keyframe the left segment's cubic is evaluated, at it the right one's.
    const double left = std::nextafter(times[i], 0.0);
    EXPECT_LT((monotone.position(left) - points[i]).norm(), 1e-13);
    EXPECT_LT((monotone.position(times[i]) - points[i]).norm(), 1e-13);
    EXPECT_LT((monotone.velocity(left) - monotone.velocity(times[i])).norm(),
              1e-12 * (1.0 + monotone.velocity(times[i]).norm()))
        << "keyframe " << i;
    EXPECT_LT((cubic.velocity(left) - cubic.velocity(times[i])).norm(), 1e-11) << "keyframe " << i;
    EXPECT_LT((cubic.acceleration(left) - cubic.acceleration(times[i])).norm(), 1e-10)
        << "keyframe " << i;
    monotone_jump = std::max(
        monotone_jump, (monotone.acceleration(left) - monotone.acceleration(times[i])).norm());
  }
  // The monotone acceleration is only piecewise continuous: it jumps at keyframes.
  EXPECT_GT(monotone_jump, 1.0);
}

TEST(TargetTrajectoryKeyframes, VelocityAndAccelerationOfEveryKindMatchDifferences) {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> points;
  random_keyframes(3, times, points);
  for (const Interpolation kind :
       {Interpolation::kMonotone, Interpolation::kCubic, Interpolation::kLinear}) {
    const TargetTrajectory target = TargetTrajectory::keyframes(times, points, kind);
    for (size_t i = 0; i + 1 < times.size(); ++i) {
      for (const double s : {0.2, 0.5, 0.8}) {  // inside the segment, away from its keyframes
        const double t = times[i] + s * (times[i + 1] - times[i]);
        const double h1 = 1e-5;
        const double h2 = 1e-4;
        const Eigen::Vector3d velocity =
            (target.position(t + h1) - target.position(t - h1)) / (2.0 * h1);
        const Eigen::Vector3d acceleration =
            (target.position(t + h2) - 2.0 * target.position(t) + target.position(t - h2)) /
            (h2 * h2);
        // Cubic pieces: central differences err by h^2 |x'''| / 6 and rounding 1e-16 |x| / h
        // (first) or / h^2 (second)
        EXPECT_LT((target.velocity(t) - velocity).norm(), 1e-7 * (1.0 + velocity.norm()))
            << static_cast<int>(kind) << " t = " << t;
        EXPECT_LT((target.acceleration(t) - acceleration).norm(),
                  1e-4 * (1.0 + acceleration.norm()))
            << static_cast<int>(kind) << " t = " << t;
      }
    }
    if (kind == Interpolation::kLinear) {
      const double t = 0.5 * (times[2] + times[3]);
      EXPECT_EQ(target.acceleration(t), Eigen::Vector3d::Zero());
      EXPECT_EQ(target.velocity(t), (points[3] - points[2]) / (times[3] - times[2]));
    }
  }
}

}  // namespace
}  // namespace dnurbs
