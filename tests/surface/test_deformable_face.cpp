#include "dnurbs/surface/deformable_face.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/restricted_mesh.h"

namespace dnurbs {
namespace {

constexpr std::array<const char*, 3> kIndividuals = {"ada", "ben", "cleo"};

std::string face_path(const std::string& individual) {
  return std::string(DNURBS_TEST_DATA_DIR) + "/../../examples/faces/face_" + individual + ".gim";
}

constexpr std::array<FaceParameter, kFaceParameterCount> kParameters = {
    FaceParameter::kFrontalisLeft,  FaceParameter::kFrontalisRight, FaceParameter::kZygomaticLeft,
    FaceParameter::kZygomaticRight, FaceParameter::kRisoriusLeft,   FaceParameter::kRisoriusRight,
    FaceParameter::kJawOpen};

// A smile, a raised brow (more on the left) and an open jaw.
Eigen::VectorXd expression() {
  Eigen::VectorXd q(kFaceParameterCount);
  q << 1.0, 0.6, 0.8, 0.8, 0.3, 0.3, 0.7;
  return q;
}

TEST(DeformableFace, RestSurfaceReproducesTheGeometryImageSamplesAtItsNodes) {
  for (const char* individual : kIndividuals) {
    const DeformableFace face = DeformableFace::read(face_path(individual));
    EXPECT_EQ(face.individual(), individual);
    const SampledVectorField& image = face.geometry_image();
    ASSERT_EQ(image.count_u(), 65);
    ASSERT_EQ(image.count_v(), 65);
    const ParametricSurface rest = face.surface(Eigen::VectorXd::Zero(kFaceParameterCount));
    for (int i = 0; i < 65; ++i) {
      for (int j = 0; j < 65; ++j) {
        // 64 cells: the node parameters i / 64 are exact in binary, so the bilinear weights are
        // exactly 0 and 1 and the fields' q_k = 0 terms add exact zeros (Goldenstein et al.
        // 2005, section 3.3: the field reproduces its samples)
        const Eigen::Vector3d point = rest.point(i / 64.0, j / 64.0);
        const Eigen::Vector3d sample = image.samples().row(i * 65 + j).transpose();
        ASSERT_EQ(point, sample) << individual << " node " << i << ", " << j;
      }
    }
  }
}

TEST(DeformableFace, FeaturesSitAtTheSameParametersOnEveryIndividual) {
  // The normalized (u, v) space (Goldenstein et al. 2005, section 3): the nose tip, the highest
  // point of each face, is node (32, 27) = (1/2, FaceLayout::kNoseTipV) on every individual
  for (const char* individual : kIndividuals) {
    const DeformableFace face = DeformableFace::read(face_path(individual));
    Eigen::Index highest = 0;
    face.geometry_image().samples().col(2).maxCoeff(&highest);
    EXPECT_EQ(highest / 65, 32) << individual;
    EXPECT_EQ(highest % 65, 27) << individual;
    EXPECT_EQ(27.0 / 64, FaceLayout::kNoseTipV);
  }
}

TEST(DeformableFace, NamesItsParametersInTheOrderOfQ) {
  const DeformableFace face = DeformableFace::read(face_path("ada"));
  EXPECT_EQ(face.parameter_count(), 7);
  EXPECT_EQ(face.field().parameter_count(), 7);
  const std::vector<std::string> expected = {"frontalis_left",  "frontalis_right", "zygomatic_left",
                                             "zygomatic_right", "risorius_left",   "risorius_right",
                                             "jaw_open"};
  EXPECT_EQ(face.parameter_names(), expected);
  // The cascade: the geometry image, then one AddVector stage per parameter
  ASSERT_EQ(face.field().stage_count(), 8);
  EXPECT_EQ(face.field().stage_kind(0), DeformationKind::kConstant);
  for (int stage = 1; stage < 8; ++stage) {
    EXPECT_EQ(face.field().stage_kind(stage), DeformationKind::kAddVector);
  }
  EXPECT_THROW(face.surface(Eigen::VectorXd::Zero(6)), Error);
  EXPECT_THROW(face.point(Eigen::VectorXd::Zero(8), 0.5, 0.5), Error);
}

TEST(DeformableFace, DisplacementIsQTimesEachVectorField) {
  const DeformableFace face = DeformableFace::read(face_path("ben"));
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(kFaceParameterCount);
  const Eigen::VectorXd q = expression();
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0 + 0.003;
      const double v = j / 40.0 - 0.002;
      Eigen::Vector3d expected = Eigen::Vector3d::Zero();
      for (int k = 0; k < kFaceParameterCount; ++k) {
        const Eigen::Vector3d field = face_vector_field(kParameters[static_cast<size_t>(k)], u, v);
        Eigen::VectorXd single = rest;
        single(k) = -1.7;
        // p(q) - p(0) = q_k V_k (eq 4); rounding of points of size 100 mm: 1e-14
        EXPECT_LT((face.point(single, u, v) - face.point(rest, u, v) + 1.7 * field).norm(), 1e-12)
            << k << " at " << u << ", " << v;
        expected += q(k) * field;
      }
      EXPECT_LT((face.point(q, u, v) - face.point(rest, u, v) - expected).norm(), 1e-12);
    }
  }
}

TEST(DeformableFace, ParameterJacobianMatchesFiniteDifferences) {
  const DeformableFace face = DeformableFace::read(face_path("cleo"));
  const Eigen::VectorXd q = expression();
  const double step = 1e-3;
  for (const auto& [u, v] : std::array<std::pair<double, double>, 6>{
           {{0.66, 0.7}, {0.34, 0.74}, {0.6, 0.3}, {0.4, 0.35}, {0.5, 0.279}, {0.52, 0.15}}}) {
    const Eigen::Matrix3Xd jacobian = face.field().parameter_jacobian(u, v);
    ASSERT_EQ(jacobian.cols(), kFaceParameterCount);
    for (int k = 0; k < kFaceParameterCount; ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus(k) += step;
      minus(k) -= step;
      const Eigen::Vector3d difference =
          (face.point(plus, u, v) - face.point(minus, u, v)) / (2.0 * step);
      // p is affine in q, so the central difference has no truncation error; rounding of
      // points of 100 mm over 2e-3: 1e-14 / 2e-3 = 5e-12
      EXPECT_LT((jacobian.col(k) - difference).norm(), 1e-10) << k << " at " << u << ", " << v;
      EXPECT_EQ(Eigen::Vector3d(jacobian.col(k)),
                face_vector_field(kParameters[static_cast<size_t>(k)], u, v));
    }
    // At these points some field is non-zero, so the test is not vacuous
    EXPECT_GT(jacobian.norm(), 1.0) << u << ", " << v;
  }
}

TEST(DeformableFace, LeftAndRightHalvesSumToTheSymmetricFieldAndMirrorEachOther) {
  const std::array<FaceMuscle, 3> muscles = {FaceMuscle::kFrontalis, FaceMuscle::kZygomatic,
                                             FaceMuscle::kRisorius};
  for (const FaceMuscle muscle : muscles) {
    const auto left = static_cast<FaceParameter>(2 * static_cast<int>(muscle));
    const auto right = static_cast<FaceParameter>(2 * static_cast<int>(muscle) + 1);
    double largest = 0.0;
    for (int i = 0; i <= 200; ++i) {
      for (int j = 0; j <= 200; ++j) {
        const double u = i / 200.0;
        const double v = j / 200.0;
        const Eigen::Vector3d left_field = face_vector_field(left, u, v);
        const Eigen::Vector3d right_field = face_vector_field(right, u, v);
        const Eigen::Vector3d symmetric = symmetric_face_vector_field(muscle, u, v);
        // The halves never overlap, so their sum is exact (1e-15 allows one rounding)
        EXPECT_LT((left_field + right_field - symmetric).norm(), 1e-15);
        if (u <= 0.5) {
          EXPECT_EQ(left_field, Eigen::Vector3d::Zero()) << u << ", " << v;
        }
        if (u >= 0.5) {
          EXPECT_EQ(right_field, Eigen::Vector3d::Zero()) << u << ", " << v;
        }
        // Mirror images: V_right(u, v) = diag(-1, 1, 1) V_left(1 - u, v)
        const Eigen::Vector3d mirror = face_vector_field(left, 1.0 - u, v);
        EXPECT_EQ(right_field, Eigen::Vector3d(-mirror.x(), mirror.y(), mirror.z()));
        largest = std::max(largest, symmetric.norm());
      }
    }
    // The peak magnitudes (mm at q = 1): frontalis 8, zygomatic 10, risorius 8
    const double peak = muscle == FaceMuscle::kZygomatic ? 10.0 : 8.0;
    EXPECT_NEAR(largest, peak, 0.05 * peak) << static_cast<int>(muscle);
  }
  // The jaw opening is one symmetric field: x = 0, and the same at u and 1 - u (u = i / 64, so
  // that 1 - u and u - 1/2 are exact)
  for (int i = 0; i <= 64; ++i) {
    for (int j = 0; j <= 100; ++j) {
      const Eigen::Vector3d field = face_vector_field(FaceParameter::kJawOpen, i / 64.0, j / 100.0);
      EXPECT_EQ(field.x(), 0.0);
      EXPECT_EQ(field, face_vector_field(FaceParameter::kJawOpen, 1.0 - i / 64.0, j / 100.0));
    }
  }
}

TEST(DeformableFace, FieldsVanishOnTheBorderAndOutsideTheirInfluenceAreas) {
  for (const FaceParameter parameter : kParameters) {
    for (int i = 0; i <= 400; ++i) {
      const double t = i / 400.0;
      for (const auto& [u, v] :
           std::array<std::pair<double, double>, 4>{{{t, 0.0}, {t, 1.0}, {0.0, t}, {1.0, t}}}) {
        EXPECT_EQ(face_vector_field(parameter, u, v), Eigen::Vector3d::Zero())
            << static_cast<int>(parameter) << " at " << u << ", " << v;
      }
    }
  }
  // The brows move the forehead, not the eyes, the nose or the mouth
  for (const auto& [u, v] :
       std::array<std::pair<double, double>, 4>{{{0.5 + FaceLayout::kEyeOffset, FaceLayout::kEyeV},
                                                 {0.5, FaceLayout::kNoseTipV},
                                                 {0.5, FaceLayout::kMouthV},
                                                 {0.66, 0.95}}}) {
    EXPECT_EQ(face_vector_field(FaceParameter::kFrontalisLeft, u, v), Eigen::Vector3d::Zero());
  }
  // At a brow the frontalis is largest, 8 mm up the forehead, and falls monotonically to zero
  // along rays leaving the brow upward, downward, outward and inward (Goldenstein et al. 2005,
  // section 3.4)
  const Eigen::Vector3d at_brow = face_vector_field(FaceParameter::kFrontalisLeft, 0.66, 0.7);
  EXPECT_NEAR(at_brow.norm(), 8.0, 1e-14);
  EXPECT_GT(at_brow.y(), 0.0);
  const double brow_outer_u = 0.5 + FaceLayout::kBrowOuter;
  const double brow_inner_u = 0.5 + FaceLayout::kBrowInner;
  for (const auto& [start, direction] : std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 4>{
           {{{0.66, 0.7}, {0.0, 0.25}},
            {{0.66, 0.7}, {0.0, -0.1}},
            {{brow_outer_u, 0.7}, {0.1, 0.0}},
            {{brow_inner_u, 0.7}, {-brow_inner_u + 0.5, 0.0}}}}) {
    double previous = face_vector_field(FaceParameter::kFrontalisLeft, start.x(), start.y()).norm();
    EXPECT_NEAR(previous, 8.0, 1e-14);
    for (int step = 1; step <= 50; ++step) {
      const Eigen::Vector2d at = start + direction * step / 50.0;
      const double magnitude =
          face_vector_field(FaceParameter::kFrontalisLeft, at.x(), at.y()).norm();
      EXPECT_LE(magnitude, previous) << at.transpose();
      previous = magnitude;
    }
    EXPECT_EQ(previous, 0.0) << start.transpose();
  }
  // The jaw: the chin moves as one constant area, 12 mm down and back
  const Eigen::Vector3d chin = face_vector_field(FaceParameter::kJawOpen, 0.5, FaceLayout::kChinV);
  EXPECT_NEAR(chin.norm(), 12.0, 1e-13);
  EXPECT_LT(chin.y(), 0.0);
  EXPECT_EQ(face_vector_field(FaceParameter::kJawOpen, 0.55, FaceLayout::kChinV + 0.03), chin);
}

// The largest jump of the fields between parameters 2e-9 apart across the places where their
// definitions switch branches, and on a grid.
TEST(DeformableFace, FieldsAreContinuous) {
  // The steepest slope of any field is inside the mouth band, below 2000 mm per unit v (the
  // inward push 6 (1 - (s / b)^2) has slope 12 / b = 2000 at its ends, b = 0.006), so a
  // continuous field changes by at most 2000 * 2e-9 = 4e-6 over 2e-9; a branch that does not
  // match its neighbour would jump by millimetres
  const double step = 1e-9;
  const double bound = 2000.0 * 2.0 * step;
  const double band = 0.006;
  const std::vector<double> switches_v = {FaceLayout::kBrowV,         FaceLayout::kChinV,
                                          FaceLayout::kMouthV - band, FaceLayout::kMouthV + band,
                                          FaceLayout::kMouthV,        FaceLayout::kMouthV + 0.1,
                                          FaceLayout::kBrowV - 0.06,  FaceLayout::kBrowV + 0.2,
                                          FaceLayout::kChinV - 0.14,  FaceLayout::kChinV + 0.2};
  const std::vector<double> switches_u = {0.5, 0.5 - FaceLayout::kMouthHalfWidth,
                                          0.5 + FaceLayout::kMouthHalfWidth, 0.5 + 0.24,
                                          0.5 + FaceLayout::kBrowInner - 0.07};
  for (const FaceParameter parameter : kParameters) {
    double largest = 0.0;
    for (int i = 0; i <= 500; ++i) {
      const double t = i / 500.0;
      for (const double v : switches_v) {
        largest = std::max(largest, (face_vector_field(parameter, t, v + step) -
                                     face_vector_field(parameter, t, v - step))
                                        .norm());
      }
      for (const double u : switches_u) {
        largest = std::max(largest, (face_vector_field(parameter, u + step, t) -
                                     face_vector_field(parameter, u - step, t))
                                        .norm());
      }
      for (int j = 0; j <= 100; ++j) {
        const double v = j / 100.0 + 0.001;
        largest = std::max(largest, (face_vector_field(parameter, t + step, v) -
                                     face_vector_field(parameter, t - step, v))
                                        .norm());
      }
    }
    EXPECT_LT(largest, bound) << static_cast<int>(parameter);
  }
}

TEST(DeformableFace, RetargetingAppliesTheSameDisplacementsToEveryIndividual) {
  const DeformableFace ada = DeformableFace::read(face_path("ada"));
  const DeformableFace cleo = DeformableFace::read(face_path("cleo"));
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(kFaceParameterCount);
  const Eigen::VectorXd q = expression();
  double largest_displacement = 0.0;
  double largest_rest_distance = 0.0;
  for (int i = 0; i <= 50; ++i) {
    for (int j = 0; j <= 50; ++j) {
      const double u = i / 50.0;
      const double v = j / 50.0;
      const Eigen::Vector3d displacement_ada = ada.point(q, u, v) - ada.point(rest, u, v);
      const Eigen::Vector3d displacement_cleo = cleo.point(q, u, v) - cleo.point(rest, u, v);
      // The same fields over the same (u, v) (Goldenstein et al. 2005, section 6); the
      // difference is the rounding of points of 100 mm, 1e-14
      EXPECT_LT((displacement_ada - displacement_cleo).norm(), 1e-12) << u << ", " << v;
      largest_displacement = std::max(largest_displacement, displacement_ada.norm());
      largest_rest_distance =
          std::max(largest_rest_distance, (ada.point(rest, u, v) - cleo.point(rest, u, v)).norm());
    }
  }
  // The expression moves points by up to about 10 mm; the two faces at rest differ by 15.455 mm
  // (measured), at least the 10.35 mm by which cleo's forehead top (y = height / 2 at v = 1,
  // heights 196.13 and 175.42 mm) is higher than ada's
  EXPECT_GT(largest_displacement, 5.0);
  EXPECT_GT(largest_rest_distance, 10.35);
  EXPECT_NEAR(largest_rest_distance, 15.455, 0.001);
  std::printf("largest displacement %.4f mm, rest faces %.4f mm apart\n", largest_displacement,
              largest_rest_distance);
}

TEST(DeformableFace, AdaptiveTessellationOfTheDeformedFaceMeetsItsErrorBound) {
  const DeformableFace face = DeformableFace::read(face_path("ben"));
  const ParametricSurface surface = face.surface(expression());
  const double bound = 0.25;  // mm
  RestrictedMesh mesh(surface, 16, 16);
  mesh.refine(surface_error_criterion(surface, bound), 16);
  // Refinement stopped by the criterion, not the depth limit
  EXPECT_LT(mesh.max_level(), 16);
  // Goldenstein et al. 2005, eq. 7: the sampled max error of every triangle within the bound
  const SurfaceError error = mesh_surface_error(mesh, kDefaultErrorSampleOrder);
  EXPECT_LE(error.max, bound);
  // and the deformed face needs refinement beyond the base mesh (the opened mouth)
  EXPECT_GT(mesh.triangle_count(), 2 * 16 * 16);
  std::printf("%d triangles, deepest level %d, max error %.4f mm, mean %.5f mm\n",
              mesh.triangle_count(), mesh.max_level(), error.max, error.mean);
}

TEST(DeformableFace, RefusesBadFilesNamingTheFileAndTheValue) {
  const std::filesystem::path folder =
      std::filesystem::path(testing::TempDir()) / "dnurbs_deformable_face";
  std::filesystem::create_directories(folder);
  const std::string valid_header = "dnurbs-geometry-image 1\nindividual x\nnodes 2 2\n";
  const std::string samples = "0 0 0\n0 1 0\n1 0 0\n1 1 0\n";
  struct Case {
    const char* name;
    std::string text;
    const char* names;  // what the message must contain besides the path
  };
  const std::vector<Case> cases = {
      {"empty", "", "empty"},
      {"magic", "dnurbs-geometry-image 2\n" + samples, "dnurbs-geometry-image 2"},
      {"individual", "dnurbs-geometry-image 1\nnodes 2 2\n" + samples, "individual"},
      {"count", "dnurbs-geometry-image 1\nindividual x\nnodes 1 2\n0 0 0\n0 1 0\n", "\"1\""},
      {"count_word", "dnurbs-geometry-image 1\nindividual x\nnodes 2 two\n", "\"two\""},
      {"nan", valid_header + "0 0 0\n0 nan 0\n1 0 0\n1 1 0\n", "\"nan\""},
      {"overflow", valid_header + "0 0 0\n0 1 0\n1e999 0 0\n1 1 0\n", "\"1e999\""},
      {"short_line", valid_header + "0 0 0\n0 1\n1 0 0\n1 1 0\n", "2 values"},
      {"too_few", valid_header + "0 0 0\n0 1 0\n1 0 0\n", "after 3 of 4"},
      {"too_many", valid_header + samples + "2 2 2\n", "more than the 4"},
  };
  for (const Case& bad : cases) {
    const std::string path = (folder / (std::string(bad.name) + ".gim")).string();
    std::ofstream(path) << bad.text;
    try {
      DeformableFace::read(path);
      ADD_FAILURE() << bad.name << " was accepted";
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(bad.names), std::string::npos) << message;
    }
  }
  // A valid file with comments reads
  const std::string path = (folder / "valid.gim").string();
  std::ofstream(path) << "# a comment\n" << valid_header << "\n# another\n" << samples;
  const DeformableFace face = DeformableFace::read(path);
  EXPECT_EQ(face.point(Eigen::VectorXd::Zero(7), 1.0, 1.0), Eigen::Vector3d(1.0, 1.0, 0.0));
  EXPECT_THROW(DeformableFace::read((folder / "missing.gim").string()), Error);
  // A geometry image over another domain is refused
  ParameterDomain other;
  other.u_max = 2.0;
  EXPECT_THROW(DeformableFace({"y", SampledVectorField(other, 2, 2, Eigen::MatrixX3d::Zero(4, 3))}),
               Error);
}

}  // namespace
}  // namespace dnurbs
