#pragma once
// The "fit" key of scene models (docs/scene-format.md): a model's initial shape fitted to points
// with the fitters of design/, so that a scan can be fitted and then sculpted. Parsing a scene
// does not fit: fit_initial_shapes does, as its own step.

#include <filesystem>

#include <Eigen/Core>

#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// Points to fit from a file: "x y z" lines (.xyz, .txt, .csv; design/point_set.h load_points)
/// or the vertices of any mesh assimp reads. Throws Error naming the file.
Eigen::MatrixX3d read_fit_points(const std::filesystem::path& path);

/// A flat clamped uniform start of degree `degree` with `spans` knot spans per direction over
/// the principal plane of `points` (the two largest principal axes), covering their extent;
/// control points at the Greville abscissae, so x(u, v) is linear in (u, v).
NurbsSurface principal_plane_surface(const Eigen::MatrixX3d& points, int degree, int spans);
/// The same along the largest principal axis: a straight clamped uniform curve.
NurbsCurve principal_axis_curve(const Eigen::MatrixX3d& points, int degree, int spans);

/// The D-NURBS curve fitted to `points` from principal_axis_curve with fit_dnurbs_curve: the
/// model (material, settings) supplies the smoothness energy K (design/dnurbs_fitting.h).
NurbsCurve fit_scene_curve(const Eigen::MatrixX3d& points, const SceneFit& fit,
                           const DNurbsCurveMaterial& material, const DNurbsSettings& settings);
/// The D-NURBS surface fitted to `points` from principal_plane_surface with fit_dnurbs_surface.
NurbsSurface fit_scene_surface(const Eigen::MatrixX3d& points, const SceneFit& fit,
                               const DNurbsSurfaceMaterial& material,
                               const DNurbsSettings& settings);
/// Runs the pending "fit" of every model of the scene (SceneModelSpec::pending_fit): reads its
/// points (resolved against scene.directory) and fits the initial shape. Throws Error
/// "<source>: models[i].fit.points: ..." when the points cannot be read and
/// "<source>: models[i].fit: ..." when the fitter fails. A scene without fits is unchanged.
void fit_initial_shapes(Scene& scene);

}  // namespace dnurbs
