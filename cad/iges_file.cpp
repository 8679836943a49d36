#include "dnurbs/cad/iges_file.h"

#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESGeom_BSplineCurve.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <IGESSelect_WorkLibrary.hxx>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "dnurbs/cad/exchange_reader.h"
#include "dnurbs/cad/occt_nurbs.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_form.h"

namespace dnurbs {
namespace {

/// IGES unit flag 2: millimetres (dnurbs coordinates have no unit; this only labels them).
constexpr const char* kUnit = "MM";

std::vector<double> knots_of(int count, const std::function<double(int)>& knot, int first) {
  std::vector<double> knots(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    knots[static_cast<size_t>(i)] = knot(first + i);
  }
  return knots;
}

bool covers_domain(const KnotVector& knots, double start, double end) {
  const double scale = std::max(1.0, knots.domain_end() - knots.domain_start());
  return std::abs(start - knots.domain_start()) <= 1e-12 * scale &&
         std::abs(end - knots.domain_end()) <= 1e-12 * scale;
}

/// Entity 126 as it is, or nothing if its range is a part of its domain (then Open CASCADE's
/// transfer cuts the segment).
std::optional<Shape> direct_curve(const IGESGeom_BSplineCurve& entity) {
  const int degree = entity.Degree();
  if (degree < 1 || degree > kMaxDegree) {
    throw make_error("degree ", degree, " is outside 1..", kMaxDegree);
  }
  KnotVector knots(degree, knots_of(
                               degree + entity.UpperIndex() + 2,
                               [&](int i) { return entity.Knot(i); }, -degree));
  if (!covers_domain(knots, entity.UMin(), entity.UMax())) {
    return std::nullopt;
  }
  const int count = entity.NbPoles();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights(count);
  for (int i = 0; i < count; ++i) {
    const gp_Pnt pole = entity.TransformedPole(i);
    points.row(i) << pole.X(), pole.Y(), pole.Z();
    weights(i) = entity.Weight(i);
  }
  return periodic_form(NurbsCurve(std::move(knots), std::move(points), std::move(weights)));
}

/// Entity 128 as it is. Open CASCADE 7.6's IGESGeom_BSplineSurface returns the parameter
/// rectangle U(0), U(1), V(0), V(1) of the file as UMin, VMin, UMax, VMax (seen on its own
/// files), so the rectangle is accepted in either reading; one short of the knot vectors' domain
/// is a trimmed surface, refused.
Shape direct_surface(const IGESGeom_BSplineSurface& entity) {
  const int degree_u = entity.DegreeU();
  const int degree_v = entity.DegreeV();
  for (const int degree : {degree_u, degree_v}) {
    if (degree < 1 || degree > kMaxDegree) {
      throw make_error("degree ", degree, " is outside 1..", kMaxDegree);
    }
  }
  KnotVector knots_u(degree_u, knots_of(
                                   degree_u + entity.UpperIndexU() + 2,
                                   [&](int i) { return entity.KnotU(i); }, -degree_u));
  KnotVector knots_v(degree_v, knots_of(
                                   degree_v + entity.UpperIndexV() + 2,
                                   [&](int i) { return entity.KnotV(i); }, -degree_v));
  const bool whole = (covers_domain(knots_u, entity.UMin(), entity.UMax()) &&
                      covers_domain(knots_v, entity.VMin(), entity.VMax())) ||
                     (covers_domain(knots_u, entity.UMin(), entity.VMin()) &&
                      covers_domain(knots_v, entity.UMax(), entity.VMax()));
  if (!whole) {
    throw Error(
        "its parameter rectangle is a part of its knot domain (a trimmed surface); dnurbs reads "
        "untrimmed surfaces only");
  }
  const int count_u = entity.NbPolesU();
  const int count_v = entity.NbPolesV();
  Eigen::MatrixX3d points(count_u * count_v, 3);
  Eigen::VectorXd weights(count_u * count_v);
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      const gp_Pnt pole = entity.TransformedPole(i, j);
      points.row(i * count_v + j) << pole.X(), pole.Y(), pole.Z();
      weights(i * count_v + j) = entity.Weight(i, j);
    }
  }
  return periodic_form(
      NurbsSurface(std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)));
}

/// The shape of a root that is a bare B-spline entity, if it is one read as it is.
std::optional<Shape> direct_shape(IGESControl_Reader& reader, int root, const std::string& source) {
  const Handle(Standard_Transient) entity = reader.RootForTransfer(root);
  const Handle(IGESGeom_BSplineCurve) curve = Handle(IGESGeom_BSplineCurve)::DownCast(entity);
  const Handle(IGESGeom_BSplineSurface) surface = Handle(IGESGeom_BSplineSurface)::DownCast(entity);
  if (curve.IsNull() && surface.IsNull()) {
    return std::nullopt;
  }
  try {
    std::optional<Shape> shape;
    with_occt_errors(source, [&] {
      shape =
          curve.IsNull() ? std::optional<Shape>(direct_surface(*surface)) : direct_curve(*curve);
    });
    return shape;
  } catch (const Error& error) {
    throw make_error(source, ": entity ", entity_label(reader, entity), ": ", error.what());
  }
}

}  // namespace

std::string iges_text(const std::vector<Shape>& shapes) {
  silence_occt_messages();
  std::ostringstream text;
  with_occt_errors("writing IGES", [&] {
    IGESControl_Writer writer(kUnit, 0);
    for (const Shape& shape : shapes) {
      const Shape open = open_form(shape);
      if (const auto* curve = std::get_if<NurbsCurve>(&open)) {
        writer.AddGeom(to_occt(*curve));
      } else {
        writer.AddGeom(to_occt(std::get<NurbsSurface>(open)));
      }
    }
    writer.ComputeModel();
    // IGESControl_Writer::Write with the reals' format raised from 10 to 17 digits.
    IGESData_IGESWriter iges_writer(writer.Model());
    iges_writer.FloatWriter().SetFormat("%.16E");
    iges_writer.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
    if (!iges_writer.Print(text)) {
      throw Error("writing IGES: Open CASCADE could not print the model");
    }
  });
  return text.str();
}

std::vector<Shape> read_iges_file(const std::filesystem::path& path) {
  IGESControl_Reader reader;
  load_exchange_file(reader, path, "IGES");
  const std::string source = path.string();
  std::vector<Shape> shapes;
  for (int root = 1; root <= reader.NbRootsForTransfer(); ++root) {
    if (std::optional<Shape> shape = direct_shape(reader, root, source)) {
      shapes.push_back(std::move(*shape));
      continue;
    }
    for (Shape& shape : transfer_root_shapes(reader, root, source)) {
      shapes.push_back(std::move(shape));
    }
  }
  return shapes;
}

}  // namespace dnurbs
