"""Topology-adaptive models on generated images and volumes: T-snakes that merge, wrap a ring
with a hole and grow through a noisy vessel tree, and T-surfaces that find a torus and a ball.

T-snakes (McInerney & Terzopoulos, "T-snakes: Topology adaptive snakes", Medical Image Analysis
4(2) 2000; Terzopoulos, "Deformable Models: Classic, Topology-Adaptive and Generalized
Formulations", 2003, section 3.1) inflate where the image is brighter than a threshold and
shrink where it is darker; after every deformation step they are reparameterized on a
Coxeter-Freudenthal grid (the ACID), so contours that touch merge and a contour that meets itself
encloses a hole. T-surfaces (same, section 3.2) do the same in a volume on a tetrahedral grid,
and the mesh's Euler characteristic chi = V - E + F tells the topology that was found (0 for a
torus, 2 for a sphere).

The images and volumes are written by scripts/generate_vision_data.py into the output folder
first. Every 2-D case writes a PNG of five panels, the image with the contours of one step each
(the seeds dashed, the steps just before and at the change of topology, the final contours;
outer boundaries orange, holes magenta); every 3-D case the final mesh as OBJ and a PNG of the
seed, intermediate meshes (the last before the Euler characteristic changes) and the final mesh.
The pictures in examples/python/pictures/ are this script's output, default mode.

    PYTHONPATH=build/python python3 examples/python/topology_adaptive.py --out topology-out
    PYTHONPATH=build/python python3 examples/python/topology_adaptive.py --out t --small
"""

import argparse
import importlib.util
import pathlib
import subprocess
import sys
import time

import numpy as np

import dnurbs

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = SOURCE_DIR / "scripts" / "generate_vision_data.py"

# The annulus of ring.png: radii 12 and 26 about (40, 40).
RING_AREA = np.pi * (26.0**2 - 12.0**2)


def generate_data(folder, seed=1):
    """Runs scripts/generate_vision_data.py into `folder` (its docstring lists the files)."""
    subprocess.run([sys.executable, str(GENERATOR), str(folder), "--seed", str(seed)],
                   check=True, stdout=subprocess.DEVNULL)


def load_generator():
    spec = importlib.util.spec_from_file_location("generate_vision_data", GENERATOR)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class _NoNoise:
    """A stand-in for the generator's random generator: normal() returns zeros."""

    @staticmethod
    def normal(mean, sigma, shape):
        return np.full(shape, float(mean))


def vessel_tree_coverage():
    """The tree's pixel coverage in [0, 1], (128, 128): the generator's vessel image without noise,
    its background gradient 0.1 + 0.08 x / 127 removed and its tube intensity 0.8 divided out."""
    image = load_generator().vessel_tree(_NoNoise())
    x = np.arange(image.shape[1], dtype=float)[None, :]
    return (image - 0.1 - 0.08 * x / 127.0) / 0.8


# ---------------------------------------------------------------------------------------------
# Measuring contours and meshes


def inside_mask(contours, shape):
    """(height, width) booleans: pixel centres (x, y) with a non-zero winding number about the
    contours (outer boundaries counter-clockwise, holes clockwise)."""
    from matplotlib.path import Path

    height, width = shape
    y, x = np.mgrid[0:height, 0:width]
    centres = np.column_stack([x.ravel(), y.ravel()]).astype(float)
    winding = np.zeros(len(centres))
    for contour in contours:
        # Path.contains_points tests one closed polygon; its sign gives the winding.
        inside = Path(contour).contains_points(centres)
        winding += np.where(inside, np.sign(dnurbs.signed_area(contour)), 0.0)
    return (winding != 0).reshape(shape)


def mesh_topology(triangles, vertex_count):
    """V, E, F, connected components (through shared edges), chi = V - E + F, and whether the
    triangles form a closed, consistently oriented 2-manifold: every vertex used, every directed
    edge once and its reverse once, and the triangles around every vertex one fan."""
    triangles = np.asarray(triangles, dtype=np.int64)
    directed = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    keys = directed[:, 0] * vertex_count + directed[:, 1]
    reverse = directed[:, 1] * vertex_count + directed[:, 0]
    unique_directed = len(np.unique(keys)) == len(keys)
    edges = np.unique(np.sort(directed, axis=1), axis=0)
    closed = unique_directed and np.isin(reverse, keys).all()
    used = np.zeros(vertex_count, dtype=bool)
    used[triangles.ravel()] = True
    # One fan per vertex: the link edges (b -> c of every triangle (a, b, c) at a) form one cycle.
    single_fans = True
    if closed:
        links = {}
        for a, b, c in np.concatenate([triangles, triangles[:, [1, 2, 0]],
                                       triangles[:, [2, 0, 1]]]):
            links.setdefault(a, {})[b] = c
        for link in links.values():
            start = next(iter(link))
            length, node = 1, link[start]
            while node != start and length <= len(link):
                node = link.get(node, start)
                length += 1
            single_fans &= length == len(link)
    # Components by union-find over the triangles' edges.
    parent = np.arange(vertex_count)

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in edges:
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[ra] = rb
    components = len({root(i) for i in np.flatnonzero(used)})
    chi = vertex_count - len(edges) + len(triangles)
    return {"vertices": vertex_count, "edges": len(edges), "triangles": len(triangles),
            "components": components, "euler_characteristic": int(chi),
            "closed_manifold": bool(closed and used.all() and single_fans)}


def enclosed_volume(vertices, triangles):
    """Sum of det(a, b, c) / 6 over the triangles: > 0 for outward (counter-clockwise) faces."""
    corners = np.asarray(vertices)[np.asarray(triangles)]
    return float(np.einsum("ij,ij->i", corners[:, 0],
                           np.cross(corners[:, 1], corners[:, 2])).sum() / 6.0)


# ---------------------------------------------------------------------------------------------
# Running the models


# The T-snakes' parameters (pixel units; the others are TSnakeParameters' defaults: tension
# 0.05, no rigidity, time step 0.2, inflation 1, edge weight 1, reparameterized every step). A
# grid of 1-px cells puts inside vertices across the thinnest twigs (3 px wide; cells of 2 px
# also work, covering 98.8% of the tree instead of 99.4%). The ramp switch F = clamp((I - 1/2) /
# 0.25, -1, 1) lets the nodes rest on the threshold contour: with the binary switch
# (inflation_band 0) they oscillate about it, the inside region never stops changing and the
# runs end at max_steps.
SNAKE_PARAMETERS = {"cell_size": 1.0, "threshold": 0.5, "inflation_band": 0.25}
STABLE_STEPS = 40  # TSnake.run's default: the region unchanged this long ends a run


def run_snake(image, seeds, max_steps, sigma=1.0):
    """A TSnake on `image` (edge potential of G_sigma * I) with a circle (centre, radius) per
    seed, stepped as TSnake.run does until the inside region is unchanged for STABLE_STEPS steps;
    returns the snake, the contours of every step [(step, [(N_i, 2) arrays])] and the seconds."""
    snake = dnurbs.TSnake(image, sigma=sigma, **SNAKE_PARAMETERS)
    for centre, radius in seeds:
        snake.add_circle(centre, radius)
    start = time.perf_counter()
    history = [(0, [np.array(contour) for contour in snake.contours])]
    stable = steps = 0
    while steps < max_steps and stable < STABLE_STEPS:
        stable = 0 if snake.step() else stable + 1
        steps += 1
        history.append((steps, [np.array(contour) for contour in snake.contours]))
    return snake, history, time.perf_counter() - start


def contour_summary(snake, history):
    """The numbers of a T-snake run: contour counts, signed areas and orientations, the enclosed
    area, the steps taken and the steps at which the number of contours changed."""
    areas = [float(dnurbs.signed_area(contour)) for contour in snake.contours]
    changes = [(step, len(contours)) for (_, before), (step, contours)
               in zip(history, history[1:]) if len(contours) != len(before)]
    return {"initial_contours": len(history[0][1]), "contours": len(snake.contours),
            "signed_areas": areas,
            "orientations": ["counter-clockwise" if a > 0 else "clockwise" for a in areas],
            "enclosed_area": float(snake.enclosed_area), "steps": history[-1][0],
            # The region last changed STABLE_STEPS before the end (unless max_steps ended it).
            "rest_step": max(history[-1][0] - STABLE_STEPS, 0),
            "contour_count_changes": changes}


def merge_discs(folder):
    """(a) Two T-snakes, one seeded in each of the overlapping discs of discs_merge.png, grow
    and merge into one contour around both."""
    image = dnurbs.read_image(str(folder / "discs_merge.png"))
    snake, history, seconds = run_snake(image, [([34.0, 32.0], 4.0), ([62.0, 32.0], 4.0)], 400)
    result = contour_summary(snake, history)
    result.update(object_area=float(image.pixels.sum()), seconds=seconds)
    return image, history, result


def wrap_ring(folder):
    """(b) One T-snake seeded in the annulus of ring.png grows around it and meets itself: it
    ends as two contours, the outer one counter-clockwise and the hole clockwise."""
    image = dnurbs.read_image(str(folder / "ring.png"))
    snake, history, seconds = run_snake(image, [([59.0, 40.0], 4.0)], 600)
    result = contour_summary(snake, history)
    result.update(object_area=float(image.pixels.sum()), annulus_area=RING_AREA, seconds=seconds)
    return image, history, result


def grow_vessels(folder):
    """(c) One T-snake seeded at the root of the noisy vessel_tree.png grows up the trunk and
    into every branch; the result is compared with the tree's pixels (coverage >= 1/2)."""
    image = dnurbs.read_image(str(folder / "vessel_tree.png"))
    snake, history, seconds = run_snake(image, [([64.0, 118.0], 2.0)], 1500)
    result = contour_summary(snake, history)
    coverage = vessel_tree_coverage()
    tree = coverage >= 0.5
    inside = inside_mask(snake.contours, tree.shape)
    result.update(tree_pixels=int(tree.sum()), tree_area=float(coverage.sum()),
                  tree_fraction_covered=float((inside & tree).sum() / tree.sum()),
                  background_pixels_inside=int((inside & ~tree).sum()), seconds=seconds)
    return image, history, result


def pick_steps(history, result):
    """Five states of a T-snake run to draw: with a change of the contour count at step k, steps
    0, k / 2, k - 1, k and the end; without, 0, 1/6, 1/3 and 2/3 of the rest step and the end."""
    last = len(history) - 1
    if result["contour_count_changes"]:
        change = result["contour_count_changes"][0][0]
        steps = (0, change // 2, change - 1, change, last)
    else:
        rest = result["rest_step"]
        steps = (0, rest // 6, rest // 3, (2 * rest) // 3, last)
    return [history[k] for k in steps]


def copy_mesh(surface):
    mesh = surface.mesh
    return np.array(mesh.vertices), np.array(mesh.triangles)


def find_shape(folder, name, seed_centre, seed_radius, max_steps, cell_size, midway):
    """(d) A T-surface seeded by a small ball in `name`.nrrd, run until the inside region is
    unchanged for 30 steps (TSurface.run's default); writes the final mesh as OBJ. Returns the
    meshes (vertices, triangles) to draw [(step, mesh)]: the seed, step `midway`, the step before
    the first change of the Euler characteristic (if any) and the end, and the numbers."""
    volume = dnurbs.read_nrrd(str(folder / f"{name}.nrrd"))
    voxels = volume.voxels / 255.0  # uchar as stored: intensities in [0, 1], threshold 1/2
    # TSurfaceParameters' defaults but the grid (tension 0.2, time step 0.25, the ramp switch of
    # band 0.25 about the threshold 1/2, reparameterized every step): cells of 1 voxel put about
    # 10 across the torus's tube, cells of 2 (small mode) about 5.
    surface = dnurbs.TSurface(dnurbs.Volume(voxels), sigma=1.0, cell_size=cell_size,
                              threshold=0.5)
    surface.add_sphere(seed_centre, seed_radius)
    start = time.perf_counter()
    history = [(0, copy_mesh(surface))]
    previous, changed_at = history[0], None
    stable = steps = 0
    while steps < max_steps and stable < 30:
        stable = 0 if surface.step() else stable + 1
        steps += 1
        current = (steps, copy_mesh(surface))
        if steps == midway:
            history.append(current)
        # chi = V - E + F = V - F / 2 on a closed mesh (every edge bounds two triangles).
        if changed_at is None and (len(current[1][0]) - len(current[1][1]) / 2
                                   != len(previous[1][0]) - len(previous[1][1]) / 2):
            changed_at = steps
            if previous[0] > midway:
                history.append(previous)
        previous = current
    history.append(previous)
    seconds = time.perf_counter() - start
    vertices, triangles = previous[1]
    result = mesh_topology(triangles, len(vertices))
    result.update(steps=steps, seconds=seconds, euler_characteristic_changed_at=changed_at,
                  enclosed_volume=enclosed_volume(vertices, triangles),
                  object_volume=float(voxels.sum()),
                  genus=(2 * result["components"] - result["euler_characteristic"]) // 2)
    mesh = surface.mesh
    mesh.name = name
    obj = folder / f"t_surface_{name}.obj"
    dnurbs.export_meshes([mesh], str(obj))
    result["obj"] = obj
    return history, result


# ---------------------------------------------------------------------------------------------
# Pictures


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


OUTER, HOLE = "#ff7f0e", "#e020c0"


def plot_panels(image, states, title, path, panel_width=2.0, dpi=100):
    """One panel per state (step, contours): the image in grey with that step's contours, outer
    boundaries (signed area > 0) orange and holes magenta, the seed's dashed; each panel's title
    gives the step, the number of contours and their signed areas (y down, as the image's rows,
    so a counter-clockwise contour of the (x, y) frame turns clockwise on the screen)."""
    plt = _pyplot()
    pixels = image.pixels
    height = panel_width * pixels.shape[0] / pixels.shape[1]
    figure_height = height + 0.6  # room for the panels' titles and the figure's
    figure, panels = plt.subplots(1, len(states), figsize=(panel_width * len(states),
                                                           figure_height))
    for index, (axes, (step, contours)) in enumerate(zip(panels, states)):
        axes.imshow(pixels, cmap="gray", vmin=0.0, vmax=1.0, interpolation="nearest")
        axes.set_xlim(-0.5, pixels.shape[1] - 0.5)
        axes.set_ylim(pixels.shape[0] - 0.5, -0.5)
        axes.set_axis_off()
        areas = [dnurbs.signed_area(contour) for contour in contours]
        for contour, area in zip(contours, areas):
            closed = np.vstack([contour, contour[:1]])
            axes.plot(closed[:, 0], closed[:, 1], color=OUTER if area > 0 else HOLE,
                      linewidth=1.2, linestyle="--" if index == 0 else "-")
        label = "final step" if index == len(states) - 1 else "step"
        axes.set_title(f"{label} {step}: {len(contours)} contour{'s' * (len(contours) != 1)}\n"
                       "area " + ", ".join(f"{area:+.0f}" for area in areas), fontsize=7)
    figure.suptitle(title, fontsize=8)
    figure.tight_layout(pad=0.2, rect=(0.0, 0.0, 1.0, 1.0 - 0.25 / figure_height))
    figure.savefig(path, dpi=dpi)
    plt.close(figure)


def plot_meshes(history, title, path, dpi=100):
    """One panel per mesh (step, (vertices, triangles)), Lambert-shaded from one light, all on
    the same box (equal scales), titled with the step and the Euler characteristic."""
    plt = _pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    figure = plt.figure(figsize=(1.9 * len(history), 2.3))
    everything = np.vstack([vertices for _, (vertices, _) in history])
    low, high = everything.min(axis=0), everything.max(axis=0)
    centre, half = (low + high) / 2, (high - low) / 2 * 1.02
    light = np.array([-0.4, -0.5, 0.77])
    for index, (step, (vertices, triangles)) in enumerate(history):
        axes = figure.add_subplot(1, len(history), index + 1, projection="3d")
        corners = vertices[triangles]
        normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-12)[:, None]
        shade = 0.3 + 0.7 * np.clip(normal @ light, 0.0, 1.0)
        colours = np.clip(np.array([0.80, 0.52, 0.25])[None, :] * shade[:, None], 0.0, 1.0)
        axes.add_collection3d(Poly3DCollection(corners, facecolors=colours, edgecolors="none",
                                               linewidths=0.0, antialiased=False))
        for set_limits, k in ((axes.set_xlim, 0), (axes.set_ylim, 1), (axes.set_zlim, 2)):
            set_limits(centre[k] - half[k], centre[k] + half[k])
        axes.set_box_aspect(tuple(half), zoom=1.2)
        axes.view_init(elev=35.0, azim=-60.0)
        axes.set_axis_off()
        topology = mesh_topology(triangles, len(vertices))
        label = "seed, step" if index == 0 else (
            "final step" if index == len(history) - 1 else "step")
        axes.set_title(f"{label} {step}: chi = {topology['euler_characteristic']}",
                       fontsize=7, y=1.0)
    figure.suptitle(title, fontsize=8)
    figure.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=0.86, wspace=0.0)
    figure.savefig(path, dpi=dpi)
    plt.close(figure)


# ---------------------------------------------------------------------------------------------


def run(out_dir, small=False, pictures=True):
    """Generates the data into out_dir, runs the five cases and writes their pictures (PNG) and
    meshes (OBJ) there. small: coarser T-surface grids (cell 2 voxels) for a quick run. Returns
    a dict of results per case ("discs", "ring", "vessels", "torus", "sphere") and "pictures"."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    generate_data(out_dir)
    results, pictures_written = {}, []

    cases = (("discs", merge_discs, "t_snake_discs_merge.png",
              "T-snakes: two seeds in overlapping discs merge into one contour"),
             ("ring", wrap_ring, "t_snake_ring.png",
              "T-snake in a ring: it meets itself, leaving an outer contour and a hole"),
             ("vessels", grow_vessels, "t_snake_vessel_tree.png",
              "T-snake growing through a noisy vessel tree"))
    for case, run_case, picture, title in cases:
        image, history, results[case] = run_case(out_dir)
        if pictures:
            plot_panels(image, pick_steps(history, results[case]), title, out_dir / picture,
                        panel_width=1.8)
            pictures_written.append(out_dir / picture)

    cell_size = 2.0 if small else 1.0
    for name, centre, radius, max_steps, midway, title in (
            ("torus", [38.0, 24.0, 12.0], 3.0, 600, 40,
             "T-surface in torus.nrrd: a seed in the tube grows around it and closes on itself"),
            ("sphere", [16.0, 16.0, 16.0], 3.0, 300, 10,
             "T-surface in sphere.nrrd: a seed grows to the ball")):
        history, results[name] = find_shape(out_dir, name, centre, radius, max_steps,
                                            cell_size, midway)
        if pictures:
            path = out_dir / f"t_surface_{name}.png"
            plot_meshes(history, title, path)
            pictures_written.append(path)
    results["pictures"] = pictures_written
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="topology_adaptive_out", help="output folder")
    parser.add_argument("--small", action="store_true",
                        help="coarse T-surface grids (cell 2 voxels), for a quick run")
    arguments = parser.parse_args()
    start = time.perf_counter()
    results = run(arguments.out, small=arguments.small)
    for case in ("discs", "ring", "vessels", "torus", "sphere"):
        print(case + ":")
        for key, value in results[case].items():
            print(f"  {key}: {value:.6g}" if isinstance(value, float) else f"  {key}: {value}")
    print("wrote", ", ".join(str(path) for path in results["pictures"]))
    print(f"total {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
