#!/usr/bin/python3
"""Plots and tables of the dnurbs benchmarks (bench/README.md).

Reads the CSV files of `dnurbs-bench --out DIR` (work_precision.csv, richardson.csv, scaling.csv,
scaling_fit.csv, machine.csv, needs.csv) and, if present in the same directory, springs.csv
(spring_step_bench), free_weights.csv (free_step_bench), terzopoulos_normals.csv
(normal_step_bench), evaluation.csv
(`evaluation_bench --out DIR`) and hardcase.xml (`test_hardcase --gtest_output=xml:DIR/hardcase.xml`).
Writes log-log PNGs (work_precision_<family>.png, scaling.png) into --plots and the tables into
--markdown.

Run with /usr/bin/python3 (it has matplotlib):
  /usr/bin/python3 bench/plot_results.py --data build-bench/bench-results \
      --plots bench/results --markdown bench/RESULTS.md
"""

import argparse
import csv
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend choice)


def read_csv(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def fmt(value, digits=3):
    """Number in short scientific-or-plain form for tables."""
    x = float(value)
    if x == 0.0 or not math.isfinite(x):
        return str(x)
    if 1e-2 <= abs(x) < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{digits - 1}e}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def group(rows, keys):
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[k] for k in keys), []).append(row)
    return groups


def plot_work_precision(rows, plots, relative):
    """One log-log figure per family: error against wall seconds per simulated second."""
    links = []
    for family, family_rows in group(rows, ["family"]).items():
        figure, axes = plt.subplots(figsize=(7.5, 5.0))
        lines = group(family_rows, ["integrator", "error_kind", "resolution", "quadrature"])
        for (integrator, kind, resolution, quadrature), line in sorted(lines.items()):
            line = sorted(line, key=lambda r: -float(r["dt"]))
            x = [float(r["seconds_per_simulated_second"]) for r in line]
            y = [max(float(r["error"]), 1e-17) for r in line]
            label = f"{integrator} n={resolution} q={quadrature}"
            if len({r["error_kind"] for r in family_rows}) > 1:
                label += f" {kind}"
            axes.loglog(x, y, marker="o", markersize=3, linewidth=1, label=label)
        axes.set_xlabel("wall seconds per simulated second")
        axes.set_ylabel(f"error ({', '.join(sorted({r['error_kind'] for r in family_rows}))})")
        axes.set_title(f"work-precision: {family[0]} ({family_rows[0]['case']})")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=6, ncol=2)
        figure.tight_layout()
        name = f"work_precision_{family[0]}.png"
        figure.savefig(os.path.join(plots, name), dpi=80)
        plt.close(figure)
        links.append((family[0], os.path.join(relative, name)))
    return links


def plot_scaling(rows, fit, plots, relative):
    n = [float(r["coordinates"]) for r in rows]
    step = [float(r["seconds_per_step"]) for r in rows]
    solve = [float(r["seconds_per_step"]) / float(r["ratio_to_backsubstitution"]) for r in rows]
    exponent = float(fit["seconds_per_step"])
    figure, axes = plt.subplots(figsize=(7.0, 5.0))
    axes.loglog(n, step, "o-", label=f"Newmark step (fitted exponent {exponent:.2f})")
    axes.loglog(n, solve, "s--", label="one back-substitution (floor)")
    scale = math.exp(sum(math.log(s) - exponent * math.log(c) for c, s in zip(n, step)) / len(n))
    axes.loglog(n, [scale * c**exponent for c in n], ":", color="gray", label="fit")
    axes.set_xlabel("coordinates (fixed-weight bicubic D-NURBS surface)")
    axes.set_ylabel("seconds per step")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(os.path.join(plots, "scaling.png"), dpi=80)
    plt.close(figure)
    return os.path.join(relative, "scaling.png")


def work_precision_summary(rows):
    """Per family, case, integrator and error kind: the finest resolution and quadrature, its dt
    range, the smallest error with its cost, and the observed order of the two finest dt."""
    out = []
    keys = ["family", "case", "integrator", "error_kind"]
    for key, line in group(rows, keys).items():
        finest_n = max(int(r["resolution"]) for r in line)
        finest_q = max(int(r["quadrature"]) for r in line if int(r["resolution"]) == finest_n)
        line = [r for r in line if int(r["resolution"]) == finest_n and int(r["quadrature"]) == finest_q]
        line.sort(key=lambda r: -float(r["dt"]))
        errors = [float(r["error"]) for r in line]
        order = "-"
        if len(line) >= 2 and errors[-1] > 1e-12 and errors[-2] > 0:
            ratio = float(line[-2]["dt"]) / float(line[-1]["dt"])
            order = f"{math.log(errors[-2] / errors[-1]) / math.log(ratio):.2f}"
        best = line[-1]
        out.append(list(key) + [finest_n, finest_q, f"{fmt(line[0]['dt'])} .. {fmt(best['dt'])}",
                                fmt(best["error"]), fmt(best["seconds_per_simulated_second"]), order])
    return table(["family", "case", "integrator", "error", "resolution", "quadrature", "dt",
                  "error at finest dt", "s per simulated s", "observed order"], out)


def free_weights_section(rows):
    """The free-weight step table of free_step_bench (bench/free_weights/README.md)."""
    text = ["\n## Free-weight step\n",
            "free_step_bench: curved clamped bicubic sheets and a curved cubic rod, newmark, "
            "dt = 0.01 (sheets) and 0.002 (rod). fixed: fixed weights; reference: free weights with "
            "IntegratorSettings::lean_step = false (separate assembly and forces, sparse sums, "
            "SparseCholesky); lean: the lean step (reference and lean linearly implicit); +N: up "
            "to 4 Newton iterations (tolerance 1e-10); default: IntegratorSettings{} (the lean "
            "step with the automatic Newton iterations of free weights, each step starting from "
            "the factor the last one ended with). Ratios of mean step times (the default step "
            "refactors now and then, which a median hides; its median ratio beside) and heap "
            "allocations per step from one run.\n"]
    text.append(table(["shape", "free coordinates", "fixed [s/step]", "reference / fixed",
                       "lean / fixed", "lean+N / fixed", "default / fixed",
                       "default / fixed (medians)", "reference / lean", "allocations reference",
                       "allocations lean", "allocations lean+N", "allocations default"],
                      [[r["shape"], r["free_coordinates"], fmt(r["fixed_s"]),
                        fmt(r["reference_over_fixed"]), fmt(r["lean_over_fixed"]),
                        fmt(r["lean_newton_over_fixed"]), fmt(r["default_over_fixed"]),
                        fmt(r["default_median_over_fixed"]), fmt(r["reference_over_lean"]),
                        r["allocations_reference"], r["allocations_lean"],
                        r["allocations_lean_newton"], r["allocations_default"]] for r in rows]))
    return "\n".join(text)


def springs_section(rows):
    """The implicit-springs table of spring_step_bench (bench/springs/README.md)."""
    text = ["\n## Implicit springs in the step\n",
            "spring_step_bench: clamped bicubic sheet, four springs (k = 1e3), implicit Euler, "
            "dt = 1/60. held: springs fixed; drag: spring 0's parameter and target move every "
            "step (Woodbury, no refactorization); refactor: the same drag with the springs "
            "summed into the step matrix and refactored every step. Ratios from one run.\n"]
    text.append(table(["side", "coordinates", "backend", "no springs [s/step]", "held [s/step]",
                       "held / no springs", "drag / held", "refactor / drag"],
                      [[r["side"], r["coordinates"], r["backend"], fmt(r["none_s"]),
                        fmt(r["held_s"]), fmt(r["held_over_none"]), fmt(r["drag_over_held"]),
                        fmt(r["refactor_over_drag"])] for r in rows]))
    return "\n".join(text)


def floor_section(rows, run_rows):
    """The solver-floor tables of floor_bench (bench/floor/README.md)."""
    text = ["\n## Solver floor\n",
            "floor_bench: Newmark step (dt = 0.01) of a clamped bicubic sheet with a point force, "
            "integrator defaults (constant step matrix: CHOLMOD supernodal from 16 free nodes on, "
            "SimplicialLDLT "
            "below; its triangular solves by core/supernodal_solve.h), against one three-column "
            "solve of the same scalar step matrix by CHOLMOD (cholmod_super_lsolve / ltsolve, "
            "BLAS per supernode) and by the panel solve the step uses; at the largest size also "
            "the step with SimplicialLDLT. Process CPU seconds (the shared machine's wall times "
            "vary 5x), medians of interleaved calls, ratios from one run.\n"]
    text.append(table(["side", "coordinates", "free nodes", "step [s]", "CHOLMOD solve3 [s]",
                       "step / solve3", "panel solve3 [s]", "step / panel solve3",
                       "SimplicialLDLT step [s]", "LDLT step / step"],
                      [[r["side"], r["coordinates"], r["free_nodes"], fmt(r["step_seconds"]),
                        fmt(r["cholmod_solve3_seconds"]), fmt(r["step_to_solve"]),
                        fmt(r["panel_solve3_seconds"]), fmt(r["step_to_panel_solve"]),
                        fmt(r["ldlt_step_seconds"]) if float(r["ldlt_step_seconds"]) > 0 else "-",
                        fmt(r["ldlt_step_to_step"]) if float(r["ldlt_step_to_step"]) > 0 else "-"]
                       for r in rows]))
    text.append("\nThe sheet scene (point force, a spring whose target rises, a probe, log every "
                "step) through run_scene, the path of `dnurbs run`, timed between its progress "
                "callbacks (step, energy check, log row), the first step left out.\n")
    text.append(table(["side", "steps", "run [s]", "median step [s]", "mean step [s]",
                       "steps per s"],
                      [[r["side"], r["steps"], fmt(r["run_seconds"]),
                        fmt(r["median_step_seconds"]), fmt(r["mean_step_seconds"]),
                        fmt(r["steps_per_second"])] for r in run_rows]))
    return "\n".join(text)


def terzopoulos_normals_section(rows):
    """The normal-approximation step table of normal_step_bench (bench/terzopoulos/README.md)."""
    text = ["\n## Terzopoulos surface: cost of the normal\n",
            "normal_step_bench: the paper sheet of Wu & de Melo (figures 5 and 7; clamped unit "
            "square, eta_ii = 0.1, xi = 7e-7, gamma = 0.5, a normal load of 0.01 at the centre), "
            "the seed's semi-implicit step (dt = 0.005) after 50 steps into the pressed state, "
            "with the classic normal (eq 21), the Christoffel normal (eqs 22-26) and the "
            "unnormalized one (|B_ij| = 1). Medians of interleaved single steps, ratios to the "
            "classic step from one run.\n"]
    text.append(table(["side", "nodes", "classic [s/step]", "christoffel [s/step]",
                       "unnormalized [s/step]", "christoffel / classic",
                       "unnormalized / classic"],
                      [[r["side"], r["nodes"], fmt(r["classic_s"]), fmt(r["christoffel_s"]),
                        fmt(r["unnormalized_s"]), fmt(r["christoffel_over_classic"]),
                        fmt(r["unnormalized_over_classic"])] for r in rows]))
    return "\n".join(text)


def face_refinement_section(rows):
    """The three refinement criteria on the face of face_refinement_bench (bench/face_mesh/README.md)
    next to Goldenstein et al. 2005, figure 2 and section 6."""
    text = ["\n## Adaptive face mesh: the three refinement criteria\n",
            "face_refinement_bench: the hand-crafted base of the face in (u, v) "
            "(examples/faces/face_base_uv.obj, figure 2a), made compliant (figure 2b) and refined "
            "over the neutral face_ada geometry image by the three criteria of Goldenstein et al. "
            "2005, section 5.2, next to the paper's figure 2. The adaptive criteria are set to their "
            "loosest setting whose mesh is within the unconditional mesh's largest and mean error "
            "(eqs 7 and 6, sampled at barycentric order 16); the rows '(largest error only)' match "
            "the largest error alone. Ratios are to the base mesh's counts; times are medians of "
            "interleaved refinements from one run, as ratios to the unconditional one (the paper: "
            "0.7 s for unconditional and normals, 2.5 s for the contour error).\n"]
    base = rows[0]
    unconditional = next(r for r in rows if r["mesh"].startswith("unconditional ("))
    table_rows = []
    for r in rows:
        paper = int(r["paper_vertices"]) > 0
        timed = float(r["seconds"]) > 0.0
        per_triangle = (float(r["seconds"]) / float(r["triangles"])) / (
            float(unconditional["seconds"]) / float(unconditional["triangles"]))
        table_rows.append([r["mesh"], r["setting"], r["vertices"], r["triangles"],
                           f"{r['paper_vertices']} / {r['paper_triangles']}" if paper else "-",
                           fmt(r["vertices_over_base"]),
                           fmt(r["paper_vertices_over_base"]) if paper else "-",
                           fmt(r["triangles_over_base"]),
                           fmt(r["paper_triangles_over_base"]) if paper else "-",
                           fmt(r["max_error_mm"]), fmt(r["mean_error_mm"]),
                           fmt(r["time_over_unconditional"]) if timed else "-",
                           fmt(per_triangle) if timed else "-"])
    text.append(table(["mesh", "setting", "vertices", "triangles", "paper V / T", "V / base V",
                       "paper V / base V", "T / base T", "paper T / base T", "max error [mm]",
                       "mean error [mm]", "time / unconditional", "time per triangle / "
                       "unconditional's"], table_rows))
    text.append(f"\nPaper: time / unconditional 0.7 / 0.7 = 1 for normals and 2.5 / 0.7 = 3.57 "
                f"for the contour error; per output triangle {(0.7 / 3674) / (0.7 / 6624):.3g} "
                f"and {(2.5 / 2567) / (0.7 / 6624):.3g}. Base: {base['vertices']} vertices, "
                f"{base['triangles']} triangles.\n")
    return "\n".join(text)


def hardcase_table(path):
    """Tests that recorded `measure` (RecordProperty: a <testcase> attribute in older GoogleTest,
    a <properties><property> child in newer), with value, bound and whether the test passed."""
    root = ElementTree.parse(path).getroot()
    rows = []
    for case in root.iter("testcase"):
        properties = dict(case.attrib)
        for prop in case.iter("property"):
            properties[prop.attrib.get("name", "")] = prop.attrib.get("value", "")
        if "measure" not in properties:
            continue
        passed = case.find("failure") is None and case.attrib.get("result", "completed") != "skipped"
        rows.append([f"{case.attrib.get('classname', '')}.{case.attrib.get('name', '')}",
                     properties["measure"].replace("|", "\\|"),
                     properties.get("value", ""), properties.get("bound", ""),
                     "yes" if passed else "**no**"])
    return table(["test", "measure", "value", "bound", "pass"], rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", required=True, help="directory of the CSV files")
    parser.add_argument("--plots", required=True, help="directory of the PNG files")
    parser.add_argument("--markdown", required=True, help="RESULTS.md to write")
    args = parser.parse_args()
    os.makedirs(args.plots, exist_ok=True)
    relative = os.path.relpath(args.plots, os.path.dirname(os.path.abspath(args.markdown)))

    def data(name):
        return os.path.join(args.data, name)

    for required in ["work_precision.csv", "richardson.csv", "scaling.csv", "scaling_fit.csv",
                     "machine.csv", "needs.csv"]:
        if not os.path.exists(data(required)):
            sys.exit(f"plot_results.py: missing {data(required)} (run dnurbs-bench --out DIR first)")

    work = read_csv(data("work_precision.csv"))
    scaling = read_csv(data("scaling.csv"))
    fit = {r["quantity"]: r["exponent"] for r in read_csv(data("scaling_fit.csv"))}
    links = plot_work_precision(work, args.plots, relative)
    scaling_link = plot_scaling(scaling, fit, args.plots, relative)

    md = ["# Benchmark results\n",
          "Generated by `bench/plot_results.py` from the CSV files of `scripts/bench.sh` "
          "(dnurbs-bench, Release). Wall times are from one run on the machine that ran it; "
          "errors are deterministic. See bench/README.md for what each section measures.\n"]
    md.append("## Work-precision\n")
    md.append("Plots: " + ", ".join(f"[{family}]({link})" for family, link in links) + ".\n")
    md.append(work_precision_summary(work))
    md.append("\nObserved orders of the converged (Richardson) references, from the three finest dt:\n")
    md.append(table(["family", "case", "integrator", "dt", "observed order"],
                    [[r["family"], r["case"], r["integrator"],
                      f"{fmt(r['dt_coarse'])}, {fmt(r['dt_medium'])}, {fmt(r['dt_fine'])}",
                      f"{float(r['observed_order']):.2f}"] for r in read_csv(data("richardson.csv"))]))
    md.append("\n## Scaling\n")
    md.append(f"[scaling.png]({scaling_link}): Newmark step of fixed-weight bicubic D-NURBS surfaces. "
              f"Fitted exponent (seconds per step ~ coordinates^k): k = "
              f"{float(fit['seconds_per_step']):.2f} for the step, "
              f"{float(fit['back_substitution']):.2f} for one back-substitution.\n")
    md.append(table(["coordinates", "seconds per step", "step / back-substitution"],
                    [[r["coordinates"], fmt(r["seconds_per_step"]),
                      fmt(r["ratio_to_backsubstitution"])] for r in scaling]))
    machine = read_csv(data("machine.csv"))
    md.append("\n## Machine floor\n")
    md.append(f"Streaming triad bandwidth: {fmt(machine[0]['bandwidth_gb_per_s'])} GB/s. "
              "A vector pass is three vectors of the model's size at that rate.\n")
    md.append(table(["model", "coordinates", "back-substitution [s]", "vector pass [s]", "step [s]",
                     "step / back-substitution", "step / vector pass"],
                    [[r["model"], r["coordinates"], fmt(r["back_substitution_seconds"]),
                      fmt(r["vector_pass_seconds"]), fmt(r["step_seconds"]),
                      fmt(r["step_to_back_substitution"]), fmt(r["step_to_vector_pass"])]
                     for r in machine]))
    md.append("\n## Modeling only what a scene needs\n")
    md.append(table(["model", "active coordinates (chosen)", "active coordinates (naive)",
                     "constant matrices (chosen)", "naive [s/step]", "chosen [s/step]", "saving",
                     "error against naive"],
                    [[r["model"], r["active_coordinates"], r["total_coordinates"],
                      r["constant_matrices"], fmt(r["naive_seconds_per_step"]),
                      fmt(r["chosen_seconds_per_step"]), fmt(r["saving_ratio"]),
                      r.get("error_against_naive", "-")]
                     for r in read_csv(data("needs.csv"))]))
    if os.path.exists(data("springs.csv")):
        md.append(springs_section(read_csv(data("springs.csv"))))
    if os.path.exists(data("free_weights.csv")):
        md.append(free_weights_section(read_csv(data("free_weights.csv"))))
    if os.path.exists(data("floor.csv")) and os.path.exists(data("floor_run.csv")):
        md.append(floor_section(read_csv(data("floor.csv")), read_csv(data("floor_run.csv"))))
    if os.path.exists(data("terzopoulos_normals.csv")):
        md.append(terzopoulos_normals_section(read_csv(data("terzopoulos_normals.csv"))))
    if os.path.exists(data("face_refinement.csv")):
        md.append(face_refinement_section(read_csv(data("face_refinement.csv"))))
    if os.path.exists(data("evaluation.csv")):
        md.append("\n## Evaluation\n")
        columns = ["evaluator", "degree", "rational", "evaluations_per_second", "ratio_to_occt",
                   "max_difference"]
        md.append(table(columns, [[r.get(c, "") for c in columns]
                                  for r in read_csv(data("evaluation.csv"))]))
    if os.path.exists(data("hardcase.xml")):
        md.append("\n## Hard cases\n")
        md.append(hardcase_table(data("hardcase.xml")))
    with open(args.markdown, "w") as stream:
        stream.write("\n".join(md))


if __name__ == "__main__":
    main()
