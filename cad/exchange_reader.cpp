#include "dnurbs/cad/exchange_reader.h"

#include <Interface_InterfaceModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <Standard_Failure.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopoDS_Shape.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include "dnurbs/cad/brep_shapes.h"
#include "dnurbs/core/error.h"

namespace dnurbs {

void silence_occt_messages() {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
}

void with_occt_errors(const std::string& context, const std::function<void()>& action) {
  try {
    action();
  } catch (const Standard_Failure& failure) {
    throw make_error(context, ": Open CASCADE failed: ", failure.GetMessageString());
  }
}

std::string entity_label(XSControl_Reader& reader, const Handle(Standard_Transient) & entity) {
  if (entity.IsNull()) {
    return {};
  }
  const Handle(TCollection_HAsciiString) label = reader.Model()->StringLabel(entity);
  return std::string(label.IsNull() ? "?" : label->ToCString()) + " (" +
         entity->DynamicType()->Name() + ")";
}

void load_exchange_file(XSControl_Reader& reader, const std::filesystem::path& path,
                        const std::string& format) {
  silence_occt_messages();
  const std::string source = path.string();
  IFSelect_ReturnStatus status = IFSelect_RetVoid;
  with_occt_errors(source, [&] { status = reader.ReadFile(source.c_str()); });
  if (status != IFSelect_RetDone) {
    throw make_error(source, ": not a readable ", format, " file (Open CASCADE's reader returned ",
                     static_cast<int>(status), ")");
  }
  if (reader.Model().IsNull() || reader.Model()->NbEntities() == 0) {
    throw make_error(source, ": not a readable ", format, " file (no entities)");
  }
}

namespace {

/// The entity a face or edge of the transfer's result came from, or null: the one that gave the
/// shape itself (mode 1), else any that gave a shape containing it (mode -1, the free curves of
/// a STEP GEOMETRIC_CURVE_SET).
Handle(Standard_Transient)
    entity_of(const XSControl_TransferReader& transfer, const TopoDS_Shape& part) {
  for (const int mode : {1, -1}) {
    try {
      Handle(Standard_Transient) entity = transfer.EntityFromShapeResult(part, mode);
      if (!entity.IsNull()) {
        return entity;
      }
    } catch (const Standard_Failure&) {
      continue;  // no entity of this kind
    }
  }
  return {};
}

}  // namespace

std::vector<Shape> transfer_root_shapes(XSControl_Reader& reader, int root,
                                        const std::string& source,
                                        const EntityGeometry& file_geometry) {
  const Handle(Standard_Transient) entity = reader.RootForTransfer(root);
  const std::string what = source + ": entity " + entity_label(reader, entity);
  const int shapes_before = reader.NbShapes();
  bool transferred = false;
  with_occt_errors(what, [&] { transferred = reader.TransferOneRoot(root); });
  if (!transferred) {
    throw make_error(what, ": Open CASCADE cannot transfer it to geometry");
  }
  if (reader.NbShapes() == shapes_before) {
    return {};  // no geometry (an empty representation)
  }
  const Handle(XSControl_TransferReader) transfer = reader.WS()->TransferReader();
  const BrepLabel label = [&](const TopoDS_Shape& part) {
    return entity_label(reader, entity_of(*transfer, part));
  };
  BrepGeometry geometry;
  if (file_geometry) {
    geometry = [&](const TopoDS_Shape& part) -> std::optional<Shape> {
      const Handle(Standard_Transient) entity = entity_of(*transfer, part);
      if (entity.IsNull()) {
        return std::nullopt;
      }
      try {
        return file_geometry(entity);
      } catch (const Error& error) {
        throw make_error("entity ", entity_label(reader, entity), ": ", error.what());
      }
    };
  }
  std::vector<Shape> shapes;
  with_occt_errors(what, [&] {
    shapes = shapes_from_brep(reader.Shape(reader.NbShapes()), source, label, geometry);
  });
  return shapes;
}

}  // namespace dnurbs
