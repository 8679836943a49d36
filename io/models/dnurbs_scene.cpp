#include "dnurbs/io/models/dnurbs_scene.h"

#include "dnurbs/io/scene_fit.h"

namespace dnurbs {

void SceneDNurbsCurve::run_fit(const Eigen::MatrixX3d& points) {
  curve = fit_scene_curve(points, fit.value(), material, settings);
}

std::unique_ptr<SceneModelSpec> read_dnurbs_curve_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path) {
  return SceneDNurbsCurve::read(reader, model, path);
}

void SceneDNurbsSurface::run_fit(const Eigen::MatrixX3d& points) {
  surface = fit_scene_surface(points, fit.value(), material, settings);
}

std::unique_ptr<SceneModelSpec> read_dnurbs_surface_scene(const SceneReader& reader,
                                                          const JsonValue& model,
                                                          const std::string& path) {
  return SceneDNurbsSurface::read(reader, model, path);
}

}  // namespace dnurbs
