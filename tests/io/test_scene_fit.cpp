// The "fit" key of scene models: a model's initial shape fitted to the committed point sets of
// tests/data (generate_fit_points.py) reproduces the shape they were sampled from, the fit
// round-trips through the writer, and the fitted model runs like any other.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/io/models/dnurbs_scene.h"
#include "dnurbs/io/models/superquadric_scene.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_fit.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/io/shape_file.h"
#include "tests/common/surface_comparison.h"

namespace dnurbs {
namespace {

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;

// A scene parsed and its fits run (parsing itself runs no fit).
Scene fitted_scene(const std::string& text, const std::string& source = "<string>",
                   const std::filesystem::path& directory = {}) {
  Scene scene = parse_scene_json(text, source, directory);
  fit_initial_shapes(scene);
  return scene;
}

template <typename Spec>
const Spec& as(const SceneModel& model) {
  return dynamic_cast<const Spec&>(*model.spec);
}

const char* const kSurfaceFitScene = R"json({
  "models": [{"name": "scan", "type": "dnurbs_surface",
              "fit": {"points": "fit_surface_points.xyz", "degree": 3, "spans": 2,
                      "smoothness": 0, "iterations": 10},
              "material": {"mass_density": 1, "damping_density": 1, "a10": 1, "a01": 1}}],
  "forces": [{"type": "spring", "model": "scan", "at": [0.5, 0.5], "stiffness": 5,
              "target": [1, 0.75, 2]}],
  "integrator": {"dt": 0.01},
  "run": {"steps": 3}
})json";

const char* const kSuperquadricFitScene = R"json({
  "models": [{"name": "blob", "type": "superquadric", "parts": "global",
              "fit": {"points": "fit_superquadric_points.xyz"}}],
  "integrator": {"dt": 0.01},
  "run": {"steps": 3}
})json";

TEST(SceneFit, FittedSurfaceReproducesTheSampledSurface) {
  const Scene scene = fitted_scene(kSurfaceFitScene, "fit.json", kData);
  const auto& spec = as<SceneDNurbsSurface>(scene.models[0]);
  ASSERT_TRUE(spec.fit.has_value());
  const NurbsSurface source =
      std::get<NurbsSurface>(read_shape_file(kData / "fit_surface_source.json"));
  EXPECT_EQ(spec.surface->knots_u().knots(), source.knots_u().knots());
  EXPECT_EQ(spec.surface->knots_v().knots(), source.knots_v().knots());
  // The points lie on the source (same degree and knots) and the flat start over their
  // principal plane projects each to its own parameters (generate_fit_points.py), so the first
  // least-squares solve recovers the control points up to rounding
  EXPECT_LT(testing::control_point_distance_up_to_symmetry(*spec.surface, source), 1e-8);
}

TEST(SceneFit, FittedSuperquadricReproducesTheSampledShape) {
  const Scene scene = fitted_scene(kSuperquadricFitScene, "fit.json", kData);
  const auto& spec = as<SceneSuperquadric>(scene.models[0]);
  ASSERT_TRUE(spec.fit.has_value());
  // generate_fit_points.py: sizes 1.2, 0.8, 0.6, e1 0.7, e2 1.3, taper 0.2, -0.1, no bend.
  // Exact points: the Levenberg-Marquardt polish ends at round-off; 1e-6 is what an optimizer
  // stopping tolerance would allow. Twist and shear are fitted and come back 0.
  for (int k = 11; k < 14; ++k) {
    EXPECT_NEAR(spec.shape(k), 0.0, 1e-10) << "q_s[" << k << "]";
  }
  EXPECT_NEAR(spec.shape(0), 1.0, 1e-12);
  EXPECT_NEAR(spec.shape(1), 1.2, 1e-6);
  EXPECT_NEAR(spec.shape(2), 0.8, 1e-6);
  EXPECT_NEAR(spec.shape(3), 0.6, 1e-6);
  EXPECT_NEAR(spec.shape(4), 0.7, 1e-6);
  EXPECT_NEAR(spec.shape(5), 1.3, 1e-6);
  EXPECT_NEAR(spec.shape(6), 0.2, 1e-6);
  EXPECT_NEAR(spec.shape(7), -0.1, 1e-6);
  EXPECT_NEAR(spec.shape(8), 0.0, 1e-6);
  EXPECT_LT((spec.centre - Eigen::Vector3d(0.3, -0.2, 0.5)).norm(), 1e-6);
  // Rotation 0.5 rad about (1, 2, 3) / |(1, 2, 3)|, up to the half turn about the body z axis
  // that maps this shape (no bend) to itself: R_expected^T R_fitted = diag(+-1, +-1, 1)
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d fitted = Eigen::Quaterniond(spec.orientation(0), spec.orientation(1),
                                                    spec.orientation(2), spec.orientation(3))
                                     .toRotationMatrix();
  const Eigen::Matrix3d relative = expected.transpose() * fitted;
  const double sign = relative(0, 0) > 0.0 ? 1.0 : -1.0;
  EXPECT_LT((relative - Eigen::Vector3d(sign, sign, 1.0).asDiagonal().toDenseMatrix()).norm(),
            1e-6);
}

// "twist": false and "shear": false hold them at 0 (the fitter's fit_twist, fit_shear); the keys
// are written back and a non-boolean is an error naming the key.
TEST(SceneFit, SuperquadricFitKeysHoldTwistAndShear) {
  const char* const text = R"json({
    "models": [{"name": "blob", "type": "superquadric",
                "fit": {"points": "fit_superquadric_points.xyz", "twist": false, "shear": false,
                        "bend_shape": true}}],
    "integrator": {"dt": 0.01},
    "run": {"steps": 3}})json";
  const Scene scene = fitted_scene(text, "fit.json", kData);
  const auto& spec = as<SceneSuperquadric>(scene.models[0]);
  ASSERT_TRUE(spec.fit.has_value());
  EXPECT_FALSE(spec.fit->twist);
  EXPECT_FALSE(spec.fit->shear);
  EXPECT_TRUE(spec.fit->bend_shape);
  EXPECT_EQ(spec.shape(11), 0.0);
  EXPECT_EQ(spec.shape(12), 0.0);
  EXPECT_EQ(spec.shape(13), 0.0);
  EXPECT_NEAR(spec.shape(1), 1.2, 1e-10);
  const std::string written = scene_to_json(parse_scene_json(text, "fit.json", kData));
  EXPECT_THAT(written, ::testing::HasSubstr("\"twist\": false"));
  EXPECT_THAT(written, ::testing::HasSubstr("\"bend_shape\": true"));
  std::string bad = text;
  bad.replace(bad.find("\"twist\": false"), 14, "\"twist\": 3");
  try {
    parse_scene_json(bad, "fit.json", kData);
    ADD_FAILURE() << "no error for \"twist\": 3";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("models[0].fit.twist"));
  }
}

TEST(SceneFit, FitRoundTripsThroughTheWriter) {
  for (const char* text : {kSurfaceFitScene, kSuperquadricFitScene}) {
    const Scene scene = parse_scene_json(text, "fit.json", kData);
    const std::string written = scene_to_json(scene);
    EXPECT_THAT(written, ::testing::HasSubstr("\"fit\""));
    EXPECT_THAT(written, ::testing::Not(::testing::HasSubstr("\"shape\"")));
    const Scene again = parse_scene_json(written, "written.json", kData);
    EXPECT_TRUE(again == scene) << written;
    EXPECT_EQ(scene_to_json(again), written);
  }
}

TEST(SceneFit, FittedModelsStartFromTheFitAndRun) {
  const Scene scene = fitted_scene(kSurfaceFitScene, "fit.json", kData);
  SceneSimulation simulation(scene);
  const NurbsSurface& fitted = *as<SceneDNurbsSurface>(scene.models[0]).surface;
  EXPECT_EQ(shape_to_json(*simulation.shape(0)), shape_to_json(Shape(fitted)));
  const Eigen::Vector3d before = fitted.point(0.5, 0.5);
  for (int i = 0; i < scene.step_count(); ++i) {
    simulation.step();
  }
  EXPECT_TRUE(simulation.system().coordinates().allFinite());
  // The spring pulls the middle towards (1, 0.75, 2), above the surface: it rises
  const Eigen::Vector3d after = std::get<NurbsSurface>(*simulation.shape(0)).point(0.5, 0.5);
  EXPECT_GT(after.z(), before.z());
  SceneSimulation superquadric(parse_scene_json(kSuperquadricFitScene, "fit.json", kData));
  superquadric.step();
  EXPECT_TRUE(superquadric.system().coordinates().allFinite());
}

TEST(SceneFit, CurveFitRecoversAStraightLineOfPoints) {
  // Points on the segment (0, 0, 0)-(3, 0, 0): a cubic with 2 spans reproduces it exactly
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "dnurbs_line.xyz";
  {
    std::ofstream out(file);
    for (int k = 0; k <= 20; ++k) {
      out << 3.0 * k / 20 << " 0 0\n";
    }
  }
  const std::string text = R"({"models": [{"type": "dnurbs_curve", "fit": {"points": ")" +
                           file.string() + R"(", "degree": 3, "spans": 2}}], "run": {"steps": 1}})";
  const Scene scene = fitted_scene(text);
  const NurbsCurve& curve = *as<SceneDNurbsCurve>(scene.models[0]).curve;
  EXPECT_EQ(curve.degree(), 3);
  EXPECT_EQ(curve.control_point_count(), 5);
  const Eigen::Vector3d a = curve.point(0.0);
  const Eigen::Vector3d b = curve.point(1.0);
  EXPECT_NEAR(std::min(a.x(), b.x()), 0.0, 1e-12);
  EXPECT_NEAR(std::max(a.x(), b.x()), 3.0, 1e-12);
  EXPECT_NEAR(curve.point(0.3).tail<2>().norm(), 0.0, 1e-12);
  std::filesystem::remove(file);
}

TEST(SceneFit, BadFitsNameTheirJsonPath) {
  auto message = [](const std::string& fit) {
    const std::string text =
        R"({"models": [{"type": "dnurbs_surface", "fit": )" + fit + R"(}], "run": {"steps": 1}})";
    try {
      fitted_scene(text, "bad.json", kData);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message(R"({"points": "fit_surface_points.xyz", "spans": 0})"),
              ::testing::HasSubstr("bad.json: models[0].fit.spans: expected an integer in 1.."));
  EXPECT_THAT(message(R"({"degree": 2})"),
              ::testing::HasSubstr("bad.json: models[0].fit.points: missing key"));
  // 144 points cannot determine 20 x 20 control points without smoothness
  EXPECT_THAT(message(R"({"points": "fit_surface_points.xyz", "spans": 17})"),
              ::testing::HasSubstr("bad.json: models[0].fit: "));
}

}  // namespace
}  // namespace dnurbs
