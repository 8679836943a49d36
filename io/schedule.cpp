#include "dnurbs/io/schedule.h"

#include <memory>

namespace dnurbs {

const char* interpolation_name(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kCubic:
      return "cubic";
    case Interpolation::kLinear:
      return "linear";
    case Interpolation::kMonotone:
      break;
  }
  return "monotone";
}

Eigen::Vector3d VectorSchedule::at(double time) const {
  if (times.empty()) {
    return values.front();
  }
  return TargetTrajectory::keyframes(times, values, interpolation).position(time);
}

double ScalarSchedule::at(double time) const {
  if (times.empty()) {
    return values.front();
  }
  std::vector<Eigen::Vector3d> points;
  points.reserve(values.size());
  for (double v : values) {
    points.emplace_back(v, 0.0, 0.0);
  }
  return TargetTrajectory::keyframes(times, points, interpolation).position(time).x();
}

VectorOfTime vector_of_time(const VectorSchedule& schedule) {
  if (schedule.times.empty()) {
    const Eigen::Vector3d value = schedule.values.front();
    return [value](double) { return Eigen::Vector3d(value); };
  }
  auto keyframes = std::make_shared<TargetTrajectory>(
      TargetTrajectory::keyframes(schedule.times, schedule.values, schedule.interpolation));
  return [keyframes](double t) { return keyframes->position(t); };
}

ScalarOfTime scalar_of_time(const ScalarSchedule& schedule) {
  VectorSchedule vector;
  vector.times = schedule.times;
  vector.interpolation = schedule.interpolation;
  for (double v : schedule.values) {
    vector.values.emplace_back(v, 0.0, 0.0);
  }
  VectorOfTime f = vector_of_time(vector);
  return [f](double t) { return f(t).x(); };
}

TargetTrajectory trajectory(const VectorSchedule& schedule) {
  if (schedule.times.empty()) {
    return TargetTrajectory::fixed(schedule.values.front());
  }
  return TargetTrajectory::keyframes(schedule.times, schedule.values, schedule.interpolation);
}

}  // namespace dnurbs
