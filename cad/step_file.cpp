#include "dnurbs/cad/step_file.h"

#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_GlobalFactors.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <XSControl_WorkSession.hxx>

#include <sstream>

#include "dnurbs/cad/brep_shapes.h"
#include "dnurbs/cad/exchange_reader.h"
#include "dnurbs/cad/step_geometry.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_form.h"

namespace dnurbs {

std::string step_text(const std::vector<Shape>& shapes) {
  silence_occt_messages();
  std::ostringstream text;
  with_occt_errors("writing STEP", [&] {
    // Open forms: Open CASCADE's writer clamps a periodic shape by knot insertion, which moves
    // its control points by round-off (and loses its periodic knots).
    std::vector<Shape> written;
    written.reserve(shapes.size());
    for (const Shape& shape : shapes) {
      written.push_back(open_form(shape));
    }
    STEPControl_Writer writer;
    if (writer.Transfer(brep_from_shapes(written), STEPControl_AsIs) != IFSelect_RetDone) {
      throw Error("writing STEP: Open CASCADE could not translate the shapes");
    }
    // STEPControl_Writer::Write with the reals' format raised from 12 to 17 digits.
    const Handle(StepData_StepModel) model =
        Handle(StepData_StepModel)::DownCast(writer.WS()->Model());
    StepData_StepWriter step_writer(model);
    step_writer.FloatWriter().SetFormat("%.16E");
    step_writer.SendModel(Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol()));
    if (!step_writer.Print(text)) {
      throw Error("writing STEP: Open CASCADE could not print the model");
    }
  });
  return text.str();
}

std::vector<Shape> read_step_file(const std::filesystem::path& path) {
  STEPControl_Reader reader;
  load_exchange_file(reader, path, "STEP");
  std::vector<Shape> shapes;
  for (int root = 1; root <= reader.NbRootsForTransfer(); ++root) {
    const EntityGeometry file_geometry = [](const Handle(Standard_Transient) & entity) {
      // The file's length unit in millimetres, set by the transfer of the root.
      return step_bspline_geometry(entity, StepData_GlobalFactors::Intance().LengthFactor());
    };
    for (Shape& shape : transfer_root_shapes(reader, root, path.string(), file_geometry)) {
      shapes.push_back(std::move(shape));
    }
  }
  return shapes;
}

}  // namespace dnurbs
