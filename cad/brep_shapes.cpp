#include "dnurbs/cad/brep_shapes.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dnurbs/cad/occt_nurbs.h"
#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

/// Points sampled on each boundary edge's parameter-space curve to check that it runs along the
/// border of the face's parameter rectangle (besides the edge's two ends).
constexpr int kBoundarySamples = 8;

/// Relative tolerance (of the rectangle's size) for a parameter-space point on the rectangle's
/// border, and for a face's rectangle matching a surface's domain: far above the round-off of
/// a parameter curve (1e-15 relative) and far below any trimming a designer could draw.
constexpr double kBorderTolerance = 1e-9;

struct ParameterBox {
  double u0 = 0.0;
  double u1 = 0.0;
  double v0 = 0.0;
  double v1 = 0.0;
};

int count_wires(const TopoDS_Face& face) {
  int wires = 0;
  for (TopExp_Explorer wire(face, TopAbs_WIRE); wire.More(); wire.Next()) {
    ++wires;
  }
  return wires;
}

/// True if every boundary edge of the face (a single wire) lies on the border of its
/// parameter rectangle, so that the face is the whole rectangle of its surface.
bool is_parameter_rectangle(const TopoDS_Face& face, const ParameterBox& box) {
  if (count_wires(face) != 1) {
    return false;
  }
  const double tolerance_u = kBorderTolerance * std::max(1.0, box.u1 - box.u0);
  const double tolerance_v = kBorderTolerance * std::max(1.0, box.v1 - box.v0);
  for (TopExp_Explorer explorer(face, TopAbs_EDGE); explorer.More(); explorer.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(explorer.Current());
    double first = 0.0;
    double last = 0.0;
    const Handle(Geom2d_Curve) curve = BRep_Tool::CurveOnSurface(edge, face, first, last);
    if (curve.IsNull()) {
      return false;
    }
    for (int k = 0; k <= kBoundarySamples + 1; ++k) {
      const gp_Pnt2d point = curve->Value(first + (last - first) * k / (kBoundarySamples + 1));
      const bool on_border = std::abs(point.X() - box.u0) <= tolerance_u ||
                             std::abs(point.X() - box.u1) <= tolerance_u ||
                             std::abs(point.Y() - box.v0) <= tolerance_v ||
                             std::abs(point.Y() - box.v1) <= tolerance_v;
      if (!on_border) {
        return false;
      }
    }
  }
  return true;
}

/// The curve of an edge's file geometry (`file_geometry`), if it gives one.
std::optional<NurbsCurve> file_curve(const TopoDS_Edge& edge, const BrepGeometry& file_geometry) {
  std::optional<Shape> geometry = file_geometry ? file_geometry(edge) : std::nullopt;
  if (geometry && std::holds_alternative<NurbsCurve>(*geometry)) {
    return std::get<NurbsCurve>(std::move(*geometry));
  }
  return std::nullopt;
}

/// The edge's 3-D curve and range: `file` (its file's geometry) when given, else Open CASCADE's.
Handle(Geom_Curve) edge_curve(const TopoDS_Edge& edge, const std::optional<NurbsCurve>& file,
                              double& first, double& last) {
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, first, last);
  return file ? Handle(Geom_Curve)(to_occt(*file)) : curve;
}

/// True if every boundary edge of the face (a single wire) lies, in space, on the four border
/// curves of the B-spline surface's whole domain: the check for faces whose parameter-space
/// curves a reader had to rebuild by projection and got wrong (STEP files carry none for a
/// face closed in both directions). Points are sampled on each edge and projected onto the
/// border curves; `tolerance` is a length.
bool lies_on_border(const TopoDS_Face& face, const Geom_BSplineSurface& surface, double tolerance,
                    const BrepGeometry& file_geometry) {
  double u0 = 0.0;
  double u1 = 0.0;
  double v0 = 0.0;
  double v1 = 0.0;
  surface.Bounds(u0, u1, v0, v1);
  const std::vector<Handle(Geom_Curve)> border = {surface.UIso(u0), surface.UIso(u1),
                                                  surface.VIso(v0), surface.VIso(v1)};
  for (TopExp_Explorer explorer(face, TopAbs_EDGE); explorer.More(); explorer.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(explorer.Current());
    if (BRep_Tool::Degenerated(edge)) {
      continue;
    }
    double first = 0.0;
    double last = 0.0;
    const Handle(Geom_Curve) curve = edge_curve(edge, file_curve(edge, file_geometry), first, last);
    if (curve.IsNull()) {
      return false;
    }
    for (int k = 0; k <= kBoundarySamples + 1; ++k) {
      const gp_Pnt point = curve->Value(first + (last - first) * k / (kBoundarySamples + 1));
      const bool on_border = std::any_of(border.begin(), border.end(), [&](const auto& iso) {
        GeomAPI_ProjectPointOnCurve projection(point, iso);
        return projection.NbPoints() > 0 && projection.LowerDistance() <= tolerance;
      });
      if (!on_border) {
        return false;
      }
    }
  }
  return true;
}

bool same_range(double a0, double a1, double b0, double b1) {
  const double tolerance = kBorderTolerance * std::max(1.0, b1 - b0);
  return std::abs(a0 - b0) <= tolerance && std::abs(a1 - b1) <= tolerance;
}

std::string type_name(const Handle(Standard_Transient) & geometry) {
  return geometry->DynamicType()->Name();
}

Shape face_shape(const TopoDS_Face& face, const BrepGeometry& file_geometry) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  const std::optional<Shape> geometry = file_geometry ? file_geometry(face) : std::nullopt;
  if (geometry && std::holds_alternative<NurbsSurface>(*geometry)) {
    surface = to_occt(std::get<NurbsSurface>(*geometry));
  }
  if (surface.IsNull()) {
    throw Error("it has no surface");
  }
  ParameterBox box;
  BRepTools::UVBounds(face, box.u0, box.u1, box.v0, box.v1);
  Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (!is_parameter_rectangle(face, box)) {
    if (count_wires(face) == 1 && !bspline.IsNull() &&
        lies_on_border(face, *bspline,
                       std::max(BRep_Tool::MaxTolerance(face, TopAbs_EDGE), Precision::Confusion()),
                       file_geometry)) {
      return geometry ? *geometry : Shape(from_occt(*bspline));
    }
    throw Error(
        "it is trimmed (bounded by curves other than the border of its parameter rectangle); "
        "dnurbs reads untrimmed surfaces only");
  }
  if (bspline.IsNull()) {
    // Exact NURBS form of an analytic (or Bezier, swept) surface over the face's rectangle.
    bspline = GeomConvert::SurfaceToBSplineSurface(
        new Geom_RectangularTrimmedSurface(surface, box.u0, box.u1, box.v0, box.v1));
  } else {
    double u0 = 0.0;
    double u1 = 0.0;
    double v0 = 0.0;
    double v1 = 0.0;
    bspline->Bounds(u0, u1, v0, v1);
    if (!same_range(box.u0, box.u1, u0, u1) || !same_range(box.v0, box.v1, v0, v1)) {
      bspline = Handle(Geom_BSplineSurface)::DownCast(bspline->Copy());
      bspline->Segment(box.u0, box.u1, box.v0, box.v1);
    } else if (geometry) {
      return *geometry;  // the file's own numbering of a periodic basis, kept
    }
  }
  return from_occt(*bspline);
}

Shape edge_shape(const TopoDS_Edge& edge, const BrepGeometry& file_geometry) {
  double first = 0.0;
  double last = 0.0;
  const std::optional<NurbsCurve> file = file_curve(edge, file_geometry);
  const Handle(Geom_Curve) curve = edge_curve(edge, file, first, last);
  if (curve.IsNull()) {
    throw Error("it has no 3-D curve");
  }
  Handle(Geom_BSplineCurve) bspline = Handle(Geom_BSplineCurve)::DownCast(curve);
  if (bspline.IsNull()) {
    bspline = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(curve, first, last));
  } else if (!same_range(first, last, bspline->FirstParameter(), bspline->LastParameter())) {
    bspline = Handle(Geom_BSplineCurve)::DownCast(bspline->Copy());
    bspline->Segment(first, last);
  } else if (file) {
    return *file;  // the file's own numbering of a periodic basis, kept
  }
  return from_occt(*bspline);
}

/// The shape `read` gives for a face or edge, its errors prefixed with `what` (the part's name).
Shape named_part(const std::string& what, const std::function<Shape()>& read) {
  try {
    return read();
  } catch (const Error& error) {
    throw make_error(what, ": ", error.what());
  } catch (const Standard_Failure& failure) {
    throw make_error(
        what, ": it has no exact NURBS form (Open CASCADE: ", failure.GetMessageString(), ")");
  }
}

}  // namespace

std::vector<Shape> shapes_from_brep(const TopoDS_Shape& brep, const std::string& source,
                                    const BrepLabel& label, const BrepGeometry& file_geometry) {
  const auto name = [&](const char* kind, int index, const TopoDS_Shape& part,
                        const std::string& geometry) {
    std::string text = source + ": " + kind + " " + std::to_string(index);
    const std::string file_label = label ? label(part) : std::string();
    if (!file_label.empty()) {
      text += " " + file_label;
    }
    return text + " (" + geometry + ")";
  };
  std::vector<Shape> shapes;
  int index = 0;
  for (TopExp_Explorer explorer(brep, TopAbs_FACE); explorer.More(); explorer.Next(), ++index) {
    const TopoDS_Face& face = TopoDS::Face(explorer.Current());
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    shapes.push_back(
        named_part(name("face", index, face, surface.IsNull() ? "no surface" : type_name(surface)),
                   [&] { return face_shape(face, file_geometry); }));
  }
  index = 0;
  for (TopExp_Explorer explorer(brep, TopAbs_EDGE, TopAbs_FACE); explorer.More();
       explorer.Next(), ++index) {
    const TopoDS_Edge& edge = TopoDS::Edge(explorer.Current());
    if (BRep_Tool::Degenerated(edge)) {
      continue;
    }
    double first = 0.0;
    double last = 0.0;
    const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, first, last);
    shapes.push_back(
        named_part(name("edge", index, edge, curve.IsNull() ? "no curve" : type_name(curve)),
                   [&] { return edge_shape(edge, file_geometry); }));
  }
  return shapes;
}

TopoDS_Shape brep_from_shapes(const std::vector<Shape>& shapes) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const Shape& shape : shapes) {
    if (const auto* curve = std::get_if<NurbsCurve>(&shape)) {
      builder.Add(compound, BRepBuilderAPI_MakeEdge(to_occt(*curve)).Edge());
    } else {
      builder.Add(compound, BRepBuilderAPI_MakeFace(to_occt(std::get<NurbsSurface>(shape)),
                                                    Precision::Confusion())
                                .Face());
    }
  }
  return compound;
}

}  // namespace dnurbs
