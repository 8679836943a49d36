#!/usr/bin/env python3
# Regenerates the corpus of malformed scenes (one mutation of a valid base scene each) and
# expected_messages.tsv, which tests/io/test_scene.cpp checks: python3 generate.py
import json, copy, os
base = {
  "models": [
    {"name": "sheet", "type": "dnurbs_surface",
     "shape": {"type": "nurbs_surface", "degree_u": 1, "degree_v": 1,
               "knots_u": [0, 0, 0.5, 1, 1], "knots_v": [0, 0, 0.5, 1, 1],
               "control_points": [[[0,0,0],[0,1,0],[0,2,0]],[[1,0,0],[1,1,0],[1,2,0]],[[2,0,0],[2,1,0],[2,2,0]]]},
     "material": {"mass_density": 1, "a10": 1, "a01": 1}},
    {"name": "snake", "type": "snake", "nodes": [[0,0,1],[1,0,1],[2,0,1],[3,0,1]],
     "material": {"tension": 1}}
  ],
  "forces": [
    {"type": "spring", "model": "sheet", "at": [0.5, 0.5], "stiffness": 1,
     "target": {"times": [0, 1, 2], "values": [[1,1,0],[1,1,1],[1,1,2]]}},
    {"type": "control_point", "model": "snake", "control_points": [1], "force": [0, 0, 1]}
  ],
  "constraints": [{"type": "point_target", "model": "sheet", "at": [0, 0], "target": [0, 0, 0]}],
  "integrator": {"scheme": "newmark", "dt": 0.01},
  "run": {"steps": 10},
  "probes": [{"name": "middle", "model": "sheet", "at": [0.5, 0.5]}]
}
cases = []
def case(name, mutate, *expected, raw=None):
    cases.append((name, mutate, expected, raw))
def m(f):
    return f
case("not_json", None, "(document)", "expected valid JSON", raw='{"models": [')
case("number_overflow", None, "(document): expected valid JSON at line 2, column 19: number overflow parsing '1e999'",
     raw='{"models": [],\n "run": {"steps": 1e999}}\n')
case("top_level_array", None, "(top level)", "expected an object", raw='[1, 2]\n')
def f(s): s["modles"] = []
case("unknown_top_key", f, "modles: unknown key")
def f(s): del s["models"]
case("missing_models", f, "models: missing key")
def f(s): s["models"] = []
case("empty_models", f, "models: expected at least one model")
def f(s): s["models"][0]["type"] = "nurbs"
case("unknown_model_type", f, "models[0].type: expected one of", "got string \"nurbs\"")
def f(s): del s["models"][1]["type"]
case("missing_model_type", f, "models[1].type: missing key")
def f(s): s["models"][1]["name"] = "sheet"
case("duplicate_model_name", f, "models[1].name: expected a unique model name")
def f(s): s["models"][0]["material"]["mass_density"] = -1
case("negative_mass_density", f, "models[0].material.mass_density: expected a number >= 0")
def f(s): s["models"][1]["material"]["tensoin"] = 1
case("unknown_material_key", f, "models[1].material.tensoin: unknown key")
def f(s): s["models"][0]["shape"]["knots_u"] = [0, 0, 0.5, 0.2, 1]
case("decreasing_knots", f, "models[0].shape.knots_u", "invalid knots")
def f(s): s["models"][0]["shape_file"] = "sheet.json"
case("shape_and_shape_file", f, "models[0].shape: expected exactly one of")
def f(s): del s["models"][0]["shape"]; s["models"][0]["shape_file"] = "does_not_exist.json"
case("missing_shape_file", f, "models[0].shape_file", "does not exist")
def f(s): s["models"][0]["shape"] = {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0,0,0],[1,0,0]]}
case("curve_shape_for_surface", f, "models[0].shape: expected a nurbs_surface for this model type")
def f(s): s["models"][0]["weights"] = "loose"
case("bad_weight_mode", f, "models[0].weights: expected one of fixed, free")
def f(s): s["models"][1]["boundary"] = {"clamp_border": True}
case("clamp_border_on_snake", f, "models[1].boundary.clamp_border: expected false")
def f(s): s["models"][0]["boundary"] = {"fixed_points": [99]}
case("fixed_point_out_of_range", f, "models[0]:", "control point 99 does not exist")
def f(s): s["models"][1]["nodes"] = [[0,0,0],[1,0,0]]
case("snake_too_few_nodes", f, "models[1].nodes: expected at least 3 nodes")
def f(s): s["models"][1]["nodes"][0] = [1, 2]
case("snake_node_not_a_point", f, "models[1].nodes[0]: expected [x, y, z]")
def f(s): s["forces"][0]["type"] = "torque"
case("unknown_force_type", f, "forces[0].type: expected one of point, spring, control_point, gravity, pressure")
def f(s): s["forces"][0]["model"] = "shet"
case("unknown_model_name", f, "forces[0].model: expected the name or index of a model", "unknown model name \"shet\"")
def f(s): s["forces"][0]["model"] = 5
case("model_index_out_of_range", f, "forces[0].model: expected a model index in 0..1")
def f(s): s["forces"][0]["stiffness"] = -2
case("negative_stiffness", f, "forces[0].stiffness: expected a number >= 0")
def f(s): s["forces"][0]["target"]["times"] = [0, 0, 2]
case("keyframes_not_increasing", f, "forces[0].target.times[1]: expected strictly increasing keyframe times")
def f(s): s["forces"][0]["target"]["values"] = [[1,1,0],[1,1,1]]
case("keyframe_count_mismatch", f, "forces[0].target.values: expected 3 values")
def f(s): s["forces"][0]["start"] = 2; s["forces"][0]["end"] = 1
case("end_before_start", f, "forces[0].end: expected an end time > start")
def f(s): s["forces"][1]["control_points"] = [2, 40]
case("control_point_out_of_range", f, "forces[1].control_points[1]:", "outside 0..3")
def f(s): s["forces"].append({"type": "pressure", "model": "sheet", "pressure": "high"})
case("pressure_not_a_number", f, "forces[2].pressure: expected a number or")
def f(s): s["forces"][0]["at"] = [0.1, 0.2, 0.3]
case("parameter_with_three_values", f, "forces[0].at: expected a material parameter [u] or [u, v]")
def f(s): s["constraints"][0]["type"] = "weld"
case("unknown_constraint_type", f, "constraints[0].type: expected one of point_target")
def f(s): s["constraints"][0]["alpha"] = -1
case("negative_alpha", f, "constraints[0].alpha: expected a number >= 0")
def f(s): s["constraints"][0] = {"type": "hinge", "model_a": 0, "axis_a": [[0, 0]], "model_b": 1, "axis_b": [[0], [1]]}
case("hinge_axis_malformed", f, "constraints[0].axis_a: expected two material parameters")
def f(s): s["constraints"][0] = {"type": "surface_normal", "model": "snake", "at": [0.5], "direction": [0, 0, 1]}
case("surface_normal_on_snake", f, "constraints[0]:")
def f(s): s["constraints"][0]["target"] = {"times": [0, 1], "values": [[0, 0, 0], [0, 0]]}
case("constraint_target_not_a_point", f, "constraints[0].target.values[1]: expected [x, y, z]")
def f(s): s["integrator"]["scheme"] = "rk4"
case("unknown_scheme", f, "integrator.scheme: expected one of central, implicit-euler, newmark")
def f(s): s["integrator"]["dt"] = 0
case("zero_dt", f, "integrator.dt: expected a number > 0")
def f(s): s["integrator"]["dt"] = "0.01"
case("dt_as_string", f, "integrator.dt: expected a finite number, got string \"0.01\"")
def f(s): s["run"] = {"steps": 10, "duration": 1.0}
case("steps_and_duration", f, "run: expected exactly one of \"steps\" and \"duration\"")
def f(s): del s["run"]
case("missing_run", f, "run: missing key")
def f(s): s["run"] = {"steps": 10.5}
case("fractional_steps", f, "run.steps: expected an integer in 1..100000000")
def f(s): del s["probes"][0]["at"]
case("probe_without_parameter", f, "probes[0].at: missing key")
def f(s): s["probes"][0]["name"] = "a,b"
case("probe_name_with_comma", f, "probes[0].name: expected a name of 1 to 100 letters, digits", 'got string "a,b"')
# Names become file names, CSV columns and names inside mesh files: plain names only
def f(s): s["models"][0]["name"] = "../../x"
case("model_name_is_a_path", f, "models[0].name: expected a name of 1 to 100 letters", 'got string "../../x"')
def f(s): s["models"][0]["name"] = "/etc/x"
case("model_name_is_an_absolute_path", f, "models[0].name: expected a name of", 'got string "/etc/x"')
def f(s): s["models"][1]["name"] = "rod\nv nan nan nan\nf 1 2 99999"
case("model_name_with_line_breaks", f, "models[1].name: expected a name of", 'got string "rod\\x0av nan nan nan\\x0af 1 2 99999"')
def f(s): s["models"][0]["name"] = "sheet\u0000"
case("model_name_with_nul", f, "models[0].name: expected a name of", 'got string "sheet\\x00"')
def f(s): s["models"][0]["name"] = ".hidden"
case("model_name_with_leading_dot", f, "models[0].name: expected a name of", "not starting with '.'")
def f(s): s["models"][0]["name"] = "x" * 101
case("model_name_too_long", f, "models[0].name: expected a name of 1 to 100")
def f(s): s["models"][0]["shape"]["control_points"][1][1] = [1e308, 1e308, 1e308]
case("energy_not_finite", f, "models[0]: the initial energy of model 'sheet' is not finite", "largest magnitude 1e+308")
# Material parameters are checked at load with their JSON path, not at the first step
def f(s): s["forces"][0]["at"] = [1.5, 0.5]
case("force_parameter_outside_domain", f, "forces[0].at: parameter 1.5 is outside the domain [0, 1]")
def f(s): s["constraints"][0]["at"] = [0, 2]
case("constraint_parameter_outside_domain", f, "constraints[0]: parameter 2 is outside the domain [0, 1]")
def f(s): s["probes"][0]["at"] = [0.5, -0.1]
case("probe_parameter_outside_domain", f, "probes[0].at: parameter -0.1 is outside the domain [0, 1]")
def f(s): s["probes"].append({"name": "on_snake", "model": "snake", "at": [0.5, 0.5]})
case("curve_parameter_with_v", f, "probes[1].at: model 1 (snake) is a curve: it takes one parameter [u], got [0.5, 0.5]")
def f(s): s["output"] = {"name": "../out"}
case("output_name_is_a_path", f, "output.name: expected a name of", 'got string "../out"')
def f(s): s["probes"][0]["name"] = "\u001b[2Jcleared"
case("probe_name_with_terminal_control", f, "probes[0].name: expected a name of", 'got string "\\x1b[2Jcleared"')
def f(s): s["output"] = {"format": "fbx"}
case("unknown_mesh_format", f, "output.format: expected one of obj, stl, ply, gltf, glb")
def f(s): s["output"] = {"format": ["obj", "stl", "obj"]}
case("duplicate_mesh_format", f, "output.format[2]: format \"obj\" listed twice")
def f(s): s["output"] = {"up_axis": "x"}
case("unknown_up_axis", f, "output.up_axis: expected one of z, y")
def f(s): s["output"] = {"format": []}
case("empty_mesh_formats", f, "output.format: expected a format or a non-empty array of formats")
def f(s): del s["models"][0]["shape"]; s["models"][0]["make"] = {"kind": "plane", "size": [1, -1]}
case("made_plane_negative_size", f, "models[0].make.size[1]: expected a number > 0, got -1")
def f(s): del s["models"][0]["shape"]; s["models"][0]["make"] = {"kind": "teapot"}
case("made_shape_unknown_kind", f, "models[0].make.kind: expected one of line, plane, box")
def f(s): s["models"][0]["make"] = {"kind": "plane"}
case("made_and_given_shape", f, "models[0].shape: expected exactly one of")
def f(s): s["output"] = {"resolution": 2}
case("resolution_too_small", f, "output.resolution: expected an integer in 3..1024")
def f(s): s["models"].append({"type": "superquadric", "shape": {"e1": 5}})
case("superquadric_squareness", f, "models[2].shape.e1: expected a squareness in 0.1..4")
def f(s): s["models"].append({"type": "superquadric", "orientation": [1, 1, 0, 0]})
case("non_unit_quaternion", f, "models[2].orientation: expected a unit quaternion")
def f(s): s["models"].append({"type": "terzopoulos_surface", "grid": {"nodes": [2, 5], "spacing": 0.1}})
case("grid_too_small", f, "models[2].grid.nodes[0]: expected an integer in 3..4096")
def f(s): s["models"].append({"type": "pde_surface", "grid": {"nodes": [5, 5], "spacing": 0.1}, "regions": [{"centre": [0, 0, 0], "radius": 0}]})
case("zero_region_radius", f, "models[2].regions[0].radius: expected a number > 0")
# PDE surface controls (Romero 2005, 5.2.1.2): keyed material, start frame, resets
def f(s): s["models"].append({"type": "pde_surface", "grid": {"nodes": [5, 5], "spacing": 0.1}, "material": {"density": {"times": [0, 1], "values": [1, -2]}}})
case("pde_negative_keyed_density", f, "models[2].material.density.values[1]: expected a number > 0, got -2")
def f(s): s["models"].append({"type": "pde_surface", "grid": {"nodes": [5, 5], "spacing": 0.1}, "material": {"density": {"times": [0, 0.03, 0.06, 0.1], "values": [2, 0.1, 0.1, 2], "interpolation": "cubic"}}})
case("pde_keyed_density_dips_below_zero", f, "models[2].material.density: at frame 4, the keyframes give -0.119741 at t = 0.04, expected a number > 0")
def f(s): s["models"].append({"type": "pde_surface", "grid": {"nodes": [5, 5], "spacing": 0.1}, "reset": [3, 7.5]})
case("pde_reset_not_an_integer", f, "models[2].reset[1]: expected an integer in 1..100000000, got number 7.5")
def f(s): s["models"].append({"type": "terzopoulos_surface", "grid": {"nodes": [5, 5], "spacing": 0.1}, "material": {"eta": [[1, 2], [0, 1]]}})
case("asymmetric_eta", f, "models[2]:")
def f(s): s["models"][0]["material"]["a10"] = [1]
case("material_not_a_number", f, "models[0].material.a10: expected a finite number, got an array of 1 values")

def f(s): s["models"][0]["fit"] = {"points": "../fit_surface_points.xyz"}
case("fit_and_shape", f, "models[0].fit: expected either \"fit\" or \"shape\", not both")
def f(s): del s["models"][0]["shape"]; s["models"][0]["fit"] = {"points": "does_not_exist.xyz"}
case("fit_missing_points_file", f, "models[0].fit.points:", "does_not_exist.xyz")
def f(s): del s["models"][0]["shape"]; s["models"][0]["fit"] = {"points": "../fit_surface_points.xyz", "smoothness": -1}
case("fit_negative_smoothness", f, "models[0].fit.smoothness: expected a number >= 0, got -1")
def f(s): del s["models"][0]["shape"]; s["models"][0]["fit"] = {"points": "../fit_surface_points.xyz", "knots": 4}
case("fit_unknown_key", f, "models[0].fit.knots: unknown key")
def f(s): s["models"].append({"type": "superquadric", "centre": [0, 0, 0], "fit": {"points": "../fit_superquadric_points.xyz"}})
case("fit_superquadric_with_centre", f, "models[2].fit: expected either \"fit\" or \"centre\", not both")
def f(s): del s["models"][0]["shape"]; s["models"][0]["fit"] = {"points": "../fit_surface_points.xyz", "spans": 17}
case("fit_too_few_points", f, "models[0].fit:")

def f(s): s["models"][1]["boundary"] = {"local_sculpting_margin": 1}
case("local_sculpting_on_snake", f, "models[1].boundary.local_sculpting_margin: expected no local sculpting: only D-NURBS models")
def f(s): s["models"][0]["boundary"] = {"local_sculpting_margin": -2}
case("local_sculpting_negative_margin", f, "models[0].boundary.local_sculpting_margin: expected an integer")

# swung_surface (io/models/swung_surface_scene.cpp)
def f(s): s["models"].append({"type": "swung_surface", "prototype": {"kind": "cube"}})
case("swung_unknown_prototype", f, "models[2].prototype.kind: expected one of sphere, torus, cylinder, cone, hat, open_profile")
def f(s): s["models"].append({"type": "swung_surface", "profile": {"shape": {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1], "control_points": [[1, 0.5, 0], [1, 0, 1]]}}, "trajectory": {"shape_file": "../circle.json"}})
case("swung_profile_out_of_plane", f, "models[2].profile: profile control point 0 has y = 0.5")
def f(s): s["models"].append({"type": "swung_surface", "prototype": {"kind": "sphere"}, "refine": [1, 65]})
case("swung_refine_too_fine", f, "models[2].refine[1]: expected an integer in 0..64")
def f(s): s["models"].append({"type": "swung_surface", "prototype": {"kind": "torus"}, "boundary": {"clamp_border": True}})
case("swung_closed_surface_border", f, "models[2]: this swung surface is closed")
def f(s): s["models"].append({"type": "swung_surface", "prototype": {"kind": "sphere", "minor_radius": 1}})
case("swung_prototype_unknown_key", f, "models[2].prototype.minor_radius: unknown key for a sphere prototype")

# Triangular D-NURBS surfaces (a third model appended to the base scene)
tile = {"type": "triangular_nurbs", "degree": 1, "vertices": [[0, 0], [1, 0], [0, 1]],
        "triangles": [[0, 1, 2]], "control_points": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}
def triangular(s, **keys):
    model = {"name": "tri", "type": "triangular_dnurbs_surface", "domain": {"shape": "l_shape"}}
    model.update(keys)
    s["models"].append(model)
    return model
def f(s): triangular(s, shape=copy.deepcopy(tile))
case("triangular_shape_and_domain", f, "models[2].shape: expected exactly one of \"shape\" (a triangular_nurbs shape), \"shape_file\" and \"domain\"")
def f(s): triangular(s, domain={"shape": "circle"})
case("triangular_unknown_domain", f, "models[2].domain.shape: expected one of rectangle, l_shape, square_with_hole")
def f(s): triangular(s, domain={"shape": "l_shape", "knot_radius": 0.6})
case("triangular_knot_radius_too_large", f, "models[2].domain:", "radius")
def f(s): triangular(s, domain={"shape": "l_shape", "lo": [0, 0]})
case("triangular_corner_of_l_shape", f, "models[2].domain.lo: only a rectangle has corners")
def f(s): triangular(s, domain={"shape": "rectangle", "cells": [0, 2]})
case("triangular_zero_cells", f, "models[2].domain.cells: expected [cells_u, cells_v], each 1..256")
def f(s): t = copy.deepcopy(tile); t["triangles"] = [[0, 2, 1]]; m = triangular(s, shape=t); del m["domain"]
case("triangular_clockwise_triangle", f, "models[2].shape.triangles: invalid triangulation")
def f(s): t = copy.deepcopy(tile); t["control_points"].pop(); m = triangular(s, shape=t); del m["domain"]
case("triangular_control_point_count", f, "models[2].shape.control_points: expected 3 control points")
def f(s): t = copy.deepcopy(tile); t["weights"] = [1, -1, 1]; m = triangular(s, shape=t); del m["domain"]
case("triangular_negative_weight", f, "models[2].shape.weights[1]: expected a number > 0, got -1")
def f(s): t = copy.deepcopy(tile); t["knot_clouds"] = [[[0, 0]]]; m = triangular(s, shape=t); del m["domain"]
case("triangular_knot_cloud_count", f, "models[2].shape.knot_clouds: expected 3 knot clouds")
def f(s): triangular(s, quadrature_degree=15)
case("triangular_quadrature_degree", f, "models[2].quadrature_degree: expected an integer in 0..14, got number 15")
def f(s): triangular(s, tessellation={"max_error": -1})
case("triangular_negative_max_error", f, "models[2].tessellation.max_error: expected a number >= 0, got -1")
def f(s): triangular(s, tessellation={"levels": 3})
case("triangular_tessellation_unknown_key", f, "models[2].tessellation.levels: unknown key")
def f(s): triangular(s, boundary={"fixed_points": [1000]})
case("triangular_fixed_point_out_of_range", f, "models[2]:", "control point 1000 does not exist")
def f(s): triangular(s, quadrature_points=3)
case("triangular_quadrature_points", f, "models[2].quadrature_points: unknown key for a triangular_dnurbs_surface model")

import sys
out = os.path.dirname(os.path.abspath(__file__))
# Hand-written cases (design_*.json, deformation_field_*.json: other base scenes) are kept with
# their lines of expected_messages.tsv
handwritten_prefixes = ("design_", "deformation_field_")
handwritten = [line.rstrip("\n") for line in open(os.path.join(out, "expected_messages.tsv"))
               if line.startswith(handwritten_prefixes)]
for f in os.listdir(out):
    if (f.endswith('.json') and not f.startswith(handwritten_prefixes)) or f.endswith('.tsv'):
        os.remove(os.path.join(out, f))
lines = []
for name, mutate, expected, raw in cases:
    if raw is not None:
        text = raw
    else:
        s = copy.deepcopy(base)
        mutate(s)
        text = json.dumps(s, indent=1) + "\n"
    open(os.path.join(out, name + ".json"), "w").write(text)
    lines.append(name + ".json\t" + "\t".join(expected))
lines += handwritten
open(os.path.join(out, "expected_messages.tsv"), "w").write(
    "# file<TAB>substrings its error message must contain (tests/io/test_scene.cpp)\n" + "\n".join(lines) + "\n")
print(len(cases))
