#pragma once
// What the STEP and IGES readers share: Open CASCADE's messages kept off the terminal, its
// failures turned into dnurbs errors, and the transfer of a file's roots into NURBS shapes with
// every refused entity named by its label in the file.

#include <Standard_Handle.hxx>
#include <Standard_Transient.hxx>
#include <XSControl_Reader.hxx>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// Removes Open CASCADE's default message printers (its transfer statistics and warnings go to
/// standard output otherwise); dnurbs reports what matters through Error. Safe to call often.
void silence_occt_messages();

/// Runs `action`, turning an Open CASCADE exception into Error "<context>: <its message>".
void with_occt_errors(const std::string& context, const std::function<void()>& action);

/// The entity's label and type in the file read by `reader`: "#123 (StepShape_AdvancedFace)"
/// in STEP, "D45 (IGESGeom_TrimmedSurface)" in IGES.
std::string entity_label(XSControl_Reader& reader, const Handle(Standard_Transient) & entity);

/// Reads `path` with `reader` (STEP or IGES) and checks it parsed; throws Error naming the file.
void load_exchange_file(XSControl_Reader& reader, const std::filesystem::path& path,
                        const std::string& format);

/// The NURBS geometry of a file's entity as the file holds it, or nothing (cad/step_geometry.h).
using EntityGeometry = std::function<std::optional<Shape>(const Handle(Standard_Transient)&)>;

/// The shapes of root `root` (1-based) of a loaded file: its transferred boundary
/// representation through shapes_from_brep, with a refused face or edge also named by the
/// entity it came from, and each face's or edge's geometry from `file_geometry` of its entity
/// when that gives one. Throws Error naming the root if Open CASCADE cannot transfer it.
std::vector<Shape> transfer_root_shapes(XSControl_Reader& reader, int root,
                                        const std::string& source,
                                        const EntityGeometry& file_geometry = {});

}  // namespace dnurbs
