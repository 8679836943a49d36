// IGES exchange: random shapes of every kind round trip exactly as entities 126 and 128; a file
// written by Open CASCADE's own IGES writer (faces as entities 510 and 144) reads as the shapes
// it holds; trimmed surfaces and broken files are refused, naming the entity or the file.
#include "dnurbs/cad/iges_file.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_Circle.hxx>
#include <IGESControl_Writer.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
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

/// Writes a face with Open CASCADE's own IGES writer and defaults, as faces (`brep_mode` 1,
/// entity 510) or as trimmed surfaces (0, entity 144).
void write_with_occt(const TopoDS_Shape& shape, int brep_mode, const std::filesystem::path& path) {
  silence_occt_messages();
  IGESControl_Writer writer("MM", brep_mode);
  ASSERT_TRUE(writer.AddShape(shape));
  writer.ComputeModel();
  ASSERT_TRUE(writer.Write(path.string().c_str()));
}

TEST(IgesFile, RandomCurvesAndSurfacesRoundTripExactly) {
  std::mt19937 generator(3002);
  std::vector<Shape> shapes = testing::random_exchange_curves(30, generator);
  for (Shape& surface : testing::random_exchange_surfaces(16, generator)) {
    shapes.push_back(std::move(surface));
  }
  const auto path = testing::fresh_cad_directory("iges_round_trip") / "shapes.igs";
  testing::write_text(path, iges_text(shapes));
  const std::vector<Shape> read = read_iges_file(path);
  ASSERT_EQ(read.size(), shapes.size());
  for (size_t i = 0; i < shapes.size(); ++i) {
    const testing::ShapeDifference difference = shape_difference(shapes[i], read[i]);
    EXPECT_EQ(difference.data, 0.0) << "shape " << i;
    EXPECT_EQ(difference.points, 0.0) << "shape " << i;
  }
}

Handle(Geom_BSplineSurface) wavy_surface() {
  TColgp_Array2OfPnt grid(1, 5, 1, 4);
  for (int i = 1; i <= 5; ++i) {
    for (int j = 1; j <= 4; ++j) {
      grid(i, j) = gp_Pnt(i, 0.5 * j, 0.2 * std::cos(i + j));
    }
  }
  return GeomAPI_PointsToBSplineSurface(grid).Surface();
}

TEST(IgesFile, OpenCascadesOwnFacesReadAsTheirSurfaces) {
  const Handle(Geom_BSplineSurface) wavy = wavy_surface();
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(wavy, 1e-7).Face();
  for (const int brep_mode : {0, 1}) {
    const auto path =
        testing::fresh_cad_directory("iges_occt") / ("occt_" + std::to_string(brep_mode) + ".igs");
    write_with_occt(face, brep_mode, path);
    const std::vector<Shape> read = read_iges_file(path);
    ASSERT_EQ(read.size(), 1U) << "mode " << brep_mode;
    // Open CASCADE writes IGES reals with 10 significant digits: data and points agree to that.
    const testing::ShapeDifference difference = shape_difference(Shape(from_occt(*wavy)), read[0]);
    EXPECT_LT(difference.data, 1e-9) << "mode " << brep_mode;
    EXPECT_LT(difference.points, 1e-9) << "mode " << brep_mode;
  }
}

TEST(IgesFile, ATrimmedSurfaceIsRefusedNamingItsEntity) {
  const TopoDS_Wire circle =
      BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(), 1.0)).Edge());
  const TopoDS_Face disc = BRepBuilderAPI_MakeFace(gp_Pln(), circle).Face();
  const auto path = testing::fresh_cad_directory("iges_trimmed") / "disc.igs";
  write_with_occt(disc, 0, path);
  const std::string message = testing::error_message([&] { read_iges_file(path); });
  EXPECT_THAT(message, ::testing::HasSubstr(path.string() + ": face 0 D"));
  EXPECT_THAT(message, ::testing::HasSubstr("it is trimmed"));
}

TEST(IgesFile, AnEntityNoNurbsOfDnurbsCanHoldIsRefusedNamingIt) {
  // A degree-20 curve (Open CASCADE allows 25, dnurbs 15), written by Open CASCADE.
  TColgp_Array1OfPnt poles(1, 21);
  for (int i = 1; i <= 21; ++i) {
    poles(i) = gp_Pnt(i, std::sin(i), 0.0);
  }
  const auto path = testing::fresh_cad_directory("iges_degree") / "degree20.igs";
  silence_occt_messages();
  IGESControl_Writer writer("MM", 0);
  ASSERT_TRUE(writer.AddGeom(GeomConvert::CurveToBSplineCurve(new Geom_BezierCurve(poles))));
  writer.ComputeModel();
  ASSERT_TRUE(writer.Write(path.string().c_str()));
  EXPECT_THAT(testing::error_message([&] { read_iges_file(path); }),
              ::testing::HasSubstr(path.string() +
                                   ": entity D1 (IGESGeom_BSplineCurve): degree 20 is outside "
                                   "1..15"));
}

TEST(IgesFile, ABrokenFileIsRefusedNamingIt) {
  const auto directory = testing::fresh_cad_directory("iges_broken");
  testing::write_text(directory / "text.igs", "this is not IGES\n");
  EXPECT_THAT(testing::error_message([&] { read_iges_file(directory / "text.igs"); }),
              ::testing::HasSubstr("text.igs: not a readable IGES file"));
}

}  // namespace
}  // namespace dnurbs
