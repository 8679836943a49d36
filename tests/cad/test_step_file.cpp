// STEP exchange: random shapes of every kind round trip exactly; files written by Open CASCADE
// itself (its own writer, its own 12-digit reals, analytic faces) read as the shapes they hold;
// trimmed faces and broken files are refused with the entity or the file named.
#include "dnurbs/cad/step_file.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_Circle.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include "dnurbs/cad/exchange_reader.h"
#include "dnurbs/cad/occt_nurbs.h"
#include "dnurbs/core/error.h"
#include "tests/cad/cad_test_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using testing::shape_difference;

/// Writes a boundary representation with Open CASCADE's own STEP writer and defaults.
void write_with_occt(const TopoDS_Shape& shape, const std::filesystem::path& path) {
  silence_occt_messages();
  STEPControl_Writer writer;
  ASSERT_EQ(writer.Transfer(shape, STEPControl_AsIs), IFSelect_RetDone);
  ASSERT_EQ(writer.Write(path.string().c_str()), IFSelect_RetDone);
}

TEST(StepFile, RandomCurvesAndSurfacesRoundTripExactly) {
  std::mt19937 generator(3001);
  std::vector<Shape> shapes = testing::random_exchange_curves(30, generator);
  for (Shape& surface : testing::random_exchange_surfaces(16, generator)) {
    shapes.push_back(std::move(surface));
  }
  const auto path = testing::fresh_cad_directory("step_round_trip") / "shapes.step";
  testing::write_text(path, step_text(shapes));
  const std::vector<Shape> read = read_step_file(path);
  // Faces come first, then free edges.
  ASSERT_EQ(read.size(), shapes.size());
  for (size_t i = 0; i < shapes.size(); ++i) {
    const Shape& expected = shapes[i < 16 ? 30 + i : i - 16];
    const testing::ShapeDifference difference = shape_difference(expected, read[i]);
    // 17 significant digits read back as the same doubles.
    EXPECT_EQ(difference.data, 0.0) << "shape " << i;
    EXPECT_EQ(difference.points, 0.0) << "shape " << i;
  }
}

TEST(StepFile, OpenCascadesOwnFileReadsAsTheShapesItHolds) {
  // A B-spline face interpolating a wavy grid, a full circle and a cylinder's side, written by
  // Open CASCADE with its defaults (12 significant digits).
  TColgp_Array2OfPnt grid(1, 6, 1, 5);
  for (int i = 1; i <= 6; ++i) {
    for (int j = 1; j <= 5; ++j) {
      grid(i, j) = gp_Pnt(i, j, 0.3 * std::sin(i) * std::cos(0.7 * j));
    }
  }
  const Handle(Geom_BSplineSurface) wavy = GeomAPI_PointsToBSplineSurface(grid).Surface();
  const double radius = 1.7;
  const double height = 2.5;
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(radius, height).Shape();
  TopoDS_Face side;
  for (TopExp_Explorer face(cylinder, TopAbs_FACE); face.More(); face.Next()) {
    if (BRep_Tool::Surface(TopoDS::Face(face.Current()))->DynamicType()->Name() ==
        std::string("Geom_CylindricalSurface")) {
      side = TopoDS::Face(face.Current());
    }
  }
  ASSERT_FALSE(side.IsNull());
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  builder.Add(compound, BRepBuilderAPI_MakeFace(wavy, 1e-7).Face());
  builder.Add(compound, side);
  builder.Add(compound, BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(), 0.75)).Edge());
  const auto path = testing::fresh_cad_directory("step_occt") / "occt.step";
  write_with_occt(compound, path);

  const std::vector<Shape> read = read_step_file(path);
  ASSERT_EQ(read.size(), 3U);
  // The B-spline face: its data to Open CASCADE's 12 significant digits.
  const testing::ShapeDifference difference = shape_difference(Shape(from_occt(*wavy)), read[0]);
  EXPECT_LT(difference.data, 1e-11);
  EXPECT_LT(difference.points, 1e-11);
  // The cylinder's side, converted exactly: every point at the radius, heights 0..h.
  const NurbsSurface& side_surface = std::get<NurbsSurface>(read[1]);
  double radius_error = 0.0;
  double lowest = 1e9;
  double highest = -1e9;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const double u =
          side_surface.knots_u().domain_start() +
          (side_surface.knots_u().domain_end() - side_surface.knots_u().domain_start()) * i / 20.0;
      const double v =
          side_surface.knots_v().domain_start() +
          (side_surface.knots_v().domain_end() - side_surface.knots_v().domain_start()) * j / 4.0;
      const Eigen::Vector3d point = side_surface.point(u, v);
      radius_error = std::max(radius_error, std::abs(point.head<2>().norm() - radius));
      lowest = std::min(lowest, point.z());
      highest = std::max(highest, point.z());
    }
  }
  EXPECT_LT(radius_error, 1e-11 * radius);
  EXPECT_NEAR(lowest, 0.0, 1e-11);
  EXPECT_NEAR(highest, height, 1e-11);
  // The circle, a rational B-spline: every point at its radius, and closed.
  const NurbsCurve& circle = std::get<NurbsCurve>(read[2]);
  for (int k = 0; k <= 40; ++k) {
    const double u = circle.knots().domain_start() +
                     (circle.knots().domain_end() - circle.knots().domain_start()) * k / 40.0;
    EXPECT_NEAR(circle.point(u).norm(), 0.75, 1e-11) << u;
  }
}

TEST(StepFile, ABoxReadsAsSixFlatPatches) {
  const auto path = testing::fresh_cad_directory("step_box") / "box.step";
  write_with_occt(BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape(), path);
  const std::vector<Shape> read = read_step_file(path);
  ASSERT_EQ(read.size(), 6U);  // the faces; the box's edges all bound faces
  for (const Shape& shape : read) {
    const NurbsSurface& face = std::get<NurbsSurface>(shape);
    // A face of the box lies on one of the planes x, y or z = 0 or its extent.
    const Eigen::Vector3d extent(1.0, 2.0, 3.0);
    const Eigen::Vector3d centre =
        face.point(0.5 * (face.knots_u().domain_start() + face.knots_u().domain_end()),
                   0.5 * (face.knots_v().domain_start() + face.knots_v().domain_end()));
    int on_planes = 0;
    for (int axis = 0; axis < 3; ++axis) {
      on_planes += std::abs(centre[axis]) < 1e-12 || std::abs(centre[axis] - extent[axis]) < 1e-12;
    }
    EXPECT_EQ(on_planes, 1);
  }
}

TEST(StepFile, ATrimmedFaceIsRefusedNamingItsEntity) {
  // A disc: a plane bounded by a circle.
  const TopoDS_Wire circle =
      BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(), 1.0)).Edge());
  const auto path = testing::fresh_cad_directory("step_trimmed") / "disc.step";
  write_with_occt(BRepBuilderAPI_MakeFace(gp_Pln(), circle).Face(), path);
  const std::string message = testing::error_message([&] { read_step_file(path); });
  EXPECT_THAT(message, ::testing::HasSubstr(path.string() + ": face 0 #"));
  EXPECT_THAT(message,
              ::testing::HasSubstr("(StepShape_AdvancedFace) (Geom_Plane): it is trimmed"));
  EXPECT_THAT(message, ::testing::HasSubstr("dnurbs reads untrimmed surfaces only"));
}

TEST(StepFile, ABrokenFileIsRefusedNamingIt) {
  const auto directory = testing::fresh_cad_directory("step_broken");
  testing::write_text(directory / "text.step", "this is not STEP\n");
  EXPECT_THAT(testing::error_message([&] { read_step_file(directory / "text.step"); }),
              ::testing::HasSubstr("text.step: not a readable STEP file"));
  EXPECT_THAT(testing::error_message([&] { read_step_file(directory / "missing.step"); }),
              ::testing::HasSubstr("missing.step: not a readable STEP file"));
}

}  // namespace
}  // namespace dnurbs
