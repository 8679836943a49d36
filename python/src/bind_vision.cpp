// The vision kernel (vision/): dnurbs.Image and dnurbs.Volume with their files, Gaussian
// smoothing, edge potentials P = -c |grad(G_sigma * I)|, contours, the topology-adaptive T-snakes
// and T-surfaces (McInerney & Terzopoulos, T-snakes: topology adaptive snakes, Medical Image
// Analysis 4, 2000), Kalman snakes (Terzopoulos & Szeliski, Tracking with Kalman snakes, 1992),
// and image forces on snakes and grid surfaces (dynamics/grid/snake.h;
// Terzopoulos, Deformable Models, eqs. 1.3-1.5).
//
// Images cross as NumPy arrays of shape (height, width), pixel [y, x] (row y, column x); volumes
// as (nz, ny, nx), voxel [z, y, x]. Points in images are (x, y) in pixel units, in volumes
// (x, y, z) in voxel units, as the library's.

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "dnurbs/dynamics/core/image_force.h"
#include "dnurbs/dynamics/grid/kalman_snake.h"
#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/vision/contour.h"
#include "dnurbs/vision/gaussian_filter.h"
#include "dnurbs/vision/t_snake.h"
#include "dnurbs/vision/t_surface.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

Image image_from_array(const py::object& pixels) {
  const Eigen::MatrixXd values = matrix_from_array(pixels, "pixels", -1, -1);
  Image image(static_cast<int>(values.cols()), static_cast<int>(values.rows()));
  image.values = values.transpose().array();
  return image;
}

py::array_t<double> image_pixels(const Image& image) {
  return array_from_matrix(image.values.matrix().transpose());
}

Volume volume_from_array(const py::object& voxels) {
  const py::array_t<double, py::array::c_style> values = parameter_array(voxels, "voxels");
  if (values.ndim() != 3) {
    throw make_error("voxels has ", values.ndim(), " dimensions, must be 3 (nz, ny, nx)");
  }
  Volume volume(static_cast<int>(values.shape(2)), static_cast<int>(values.shape(1)),
                static_cast<int>(values.shape(0)));
  std::copy(values.data(), values.data() + values.size(), volume.values.begin());
  return volume;
}

py::array_t<double> volume_voxels(const Volume& volume) {
  py::array_t<double> result({static_cast<py::ssize_t>(volume.size[2]),
                              static_cast<py::ssize_t>(volume.size[1]),
                              static_cast<py::ssize_t>(volume.size[0])});
  std::copy(volume.values.begin(), volume.values.end(), result.mutable_data());
  return result;
}

// The parameters of T-snakes and T-surfaces from keyword arguments; Error naming an unknown key.
template <typename Parameters>
Parameters adaptive_parameters(const py::kwargs& options) {
  Parameters parameters;
  for (const auto& [key, value] : options) {
    const auto name = py::cast<std::string>(key);
    if (name == "steps_per_reparameterization") {
      parameters.steps_per_reparameterization = py::cast<int>(value);
      continue;
    }
    double* field = name == "cell_size"        ? &parameters.cell_size
                    : name == "tension"        ? &parameters.tension
                    : name == "rigidity"       ? &parameters.rigidity
                    : name == "damping"        ? &parameters.damping
                    : name == "time_step"      ? &parameters.time_step
                    : name == "inflation"      ? &parameters.inflation
                    : name == "threshold"      ? &parameters.threshold
                    : name == "inflation_band" ? &parameters.inflation_band
                    : name == "edge_weight"    ? &parameters.edge_weight
                                               : nullptr;
    if (field == nullptr) {
      throw make_error("unknown parameter \"", name,
                       "\" (cell_size, tension, rigidity, damping, time_step, inflation, "
                       "threshold, inflation_band, edge_weight, steps_per_reparameterization)");
    }
    *field = py::cast<double>(value);
  }
  return parameters;
}

Contour contour_argument(const py::object& value) {
  return matrix_from_array(value, "contour", -1, 2);
}

std::vector<Contour> contour_list(const std::vector<py::object>& values) {
  std::vector<Contour> contours;
  contours.reserve(values.size());
  for (const py::object& value : values) {
    contours.push_back(contour_argument(value));
  }
  return contours;
}

py::list contour_arrays(const std::vector<Contour>& contours) {
  py::list result;
  for (const Contour& contour : contours) {
    result.append(array_from_matrix(contour));
  }
  return result;
}

template <int Dimension>
void bind_edge_potential(py::module_& module, const char* name, const char* doc) {
  using P = EdgePotential<Dimension>;
  using Point = typename P::Point;
  const auto per_point = [](const P& self, const py::object& points, bool gradient, bool smoothed) {
    const ItemArray items = item_array(points, "points", Dimension);
    py::array_t<double> result = gradient ? new_result(items, {Dimension}) : new_result(items, {});
    for (py::ssize_t i = 0; i < items.count; ++i) {
      const Point point = Eigen::Map<const Point>(items.item(i));
      if (gradient) {
        Eigen::Map<Point>(result.mutable_data() + Dimension * i) = self.gradient(point);
      } else {
        result.mutable_data()[i] = smoothed ? self.smoothed_intensity(point) : self.value(point);
      }
    }
    return result;
  };
  py::class_<P>(module, name, doc)
      .def(
          "value",
          [per_point](const P& self, const py::object& points) {
            return per_point(self, points, false, false);
          },
          py::arg("points"), "P at points (..., d) -> (...).")
      .def(
          "gradient",
          [per_point](const P& self, const py::object& points) {
            return per_point(self, points, true, false);
          },
          py::arg("points"),
          "grad P (the exact gradient of the interpolant) at points (..., d) -> (..., d).")
      .def(
          "smoothed_intensity",
          [per_point](const P& self, const py::object& points) {
            return per_point(self, points, false, true);
          },
          py::arg("points"), "(G_sigma * I) at points (..., d) -> (...).");
}

void bind_images(py::module_& module) {
  py::class_<Image>(module, "Image",
                    "A greyscale image with float intensities (files read to [0, 1]).")
      .def(py::init(&image_from_array), py::arg("pixels"),
           "pixels: (height, width), pixel [y, x]; copied.")
      .def_property_readonly("width", &Image::width, "Columns.")
      .def_property_readonly("height", &Image::height, "Rows.")
      .def_property_readonly("pixels", &image_pixels, "The pixels, (height, width): a new array.");
  py::class_<Volume>(module, "Volume", "A greyscale volume with float intensities.")
      .def(py::init(&volume_from_array), py::arg("voxels"),
           "voxels: (nz, ny, nx), voxel [z, y, x]; copied.")
      .def_property_readonly(
          "size", [](const Volume& self) { return self.size; }, "(nx, ny, nz).")
      .def_property_readonly("voxels", &volume_voxels, "The voxels, (nz, ny, nx): a new array.")
      .def_property_readonly(
          "spacing", [](const Volume& self) { return array_from_vector(self.spacing); },
          "Distances between voxel centres (x, y, z), (3,) (from NRRD spacings).");
  module.def("read_nrrd", &read_nrrd, py::arg("path"),
             "Reads a 3-D NRRD file (integer or float types; raw, ascii or gzip encodings) into "
             "a Volume, values as stored.");
  module.def("write_nrrd", &write_nrrd, py::arg("volume"), py::arg("path"),
             "Writes a Volume as NRRD with raw little-endian doubles (an exact round trip).");
  module.def("read_volume_slices", &read_volume_slices, py::arg("paths"),
             "A Volume from a list of PNG or PGM slices (slice k at z = k), values in [0, 1].");
  module.def("read_image", &read_image, py::arg("path"),
             "Reads a PNG or PGM file (8 or 16 bit; colour to grey) into an Image in [0, 1].");
  module.def("write_png", &write_png, py::arg("image"), py::arg("path"), py::arg("bit_depth") = 8,
             "Writes an Image as a greyscale PNG (values clamped to [0, 1]).");
  module.def("write_pgm", &write_pgm, py::arg("image"), py::arg("path"), py::arg("bit_depth") = 8,
             "Writes an Image as a binary PGM (values clamped to [0, 1]).");
  module.def(
      "gaussian_kernel", [](double sigma) { return array_from_vector(gaussian_kernel(sigma)); },
      py::arg("sigma"),
      "The sampled normalized Gaussian on taps -r..r, r = ceil(5 sigma): (2 r + 1,).");
  module.def(
      "gaussian_smooth",
      [](const Image& image, double sigma) { return gaussian_smooth(image, sigma); },
      py::arg("image"), py::arg("sigma"), "G_sigma * I (borders repeat): an Image.");
  bind_edge_potential<2>(module, "ImageEdgePotential",
                         "P = -c |grad(G_sigma * I)| of an Image, Catmull-Rom interpolated; "
                         "points are (x, y) in pixels.");
  bind_edge_potential<3>(module, "VolumeEdgePotential",
                         "P = -c |grad(G_sigma * V)| of a Volume; points are (x, y, z) in voxels.");
  module.def(
      "image_edge_potential",
      [](const Image& image, double sigma, double c) {
        return ImageEdgePotential(image, sigma, c);
      },
      py::arg("image"), py::arg("sigma"), py::arg("c") = 1.0,
      "The ImageEdgePotential of an Image (sigma in [0, 256] pixels).");
  module.def(
      "volume_edge_potential",
      [](const Volume& volume, double sigma, double c) {
        return VolumeEdgePotential(volume, sigma, c);
      },
      py::arg("volume"), py::arg("sigma"), py::arg("c") = 1.0, "The VolumeEdgePotential.");
  module.def(
      "signed_area",
      [](const py::object& contour) { return signed_area(contour_argument(contour)); },
      py::arg("contour"), "Shoelace area of a closed polygon (N, 2): > 0 counter-clockwise.");
  module.def(
      "winding_number",
      [](const std::vector<py::object>& contours, const py::object& point) {
        return winding_number(contour_list(contours),
                              matrix_from_array(point, "point", 1, 2, true).row(0).transpose());
      },
      py::arg("contours"), py::arg("point"),
      "The winding number of point (2,) about a list of contours (N_i, 2).");
  module.def(
      "contours_intersect",
      [](const std::vector<py::object>& contours) {
        return contours_intersect(contour_list(contours));
      },
      py::arg("contours"), "True if two elements of the contours touch or cross.");
}

void bind_t_snakes(py::module_& module) {
  py::class_<TSnake>(module, "TSnake",
                     "Topology-adaptive snakes on an Image (McInerney & Terzopoulos 2000): "
                     "closed contours (N, 2) in pixel units that split and merge on the ACID "
                     "grid.")
      .def(py::init([](const Image& image, double sigma, double c, const py::kwargs& options) {
             return TSnake(image, ImageEdgePotential(image, sigma, c),
                           adaptive_parameters<TSnakeParameters>(options));
           }),
           py::arg("image"), py::arg("sigma") = 1.0, py::arg("c") = 1.0,
           "The edge potential of `image` with sigma, c; keyword parameters cell_size, tension, "
           "rigidity, damping, time_step, inflation, threshold, inflation_band, edge_weight, "
           "steps_per_reparameterization (pixel units).")
      .def(
          "add_contour",
          [](TSnake& self, const py::object& contour) {
            self.add_contour(contour_argument(contour));
          },
          py::arg("contour"), "Adds the region a closed polygon (N, 2) winds around.")
      .def(
          "add_circle",
          [](TSnake& self, const py::object& center, double radius) {
            self.add_circle(matrix_from_array(center, "center", 1, 2, true).row(0).transpose(),
                            radius);
          },
          py::arg("center"), py::arg("radius"), "Adds a circular snake (a 64-gon).")
      .def("remove_contour", &TSnake::remove_contour, py::arg("index"),
           "Removes contour `index` (an outer boundary with its holes, or fills a hole).")
      .def("step", &TSnake::step,
           "One deformation step (and reparameterization every M steps); True if the inside "
           "region changed.")
      .def("run", &TSnake::run, py::arg("max_steps"), py::arg("stable_steps") = 40,
           "Steps until the region is stable for `stable_steps` steps; returns the steps taken.")
      .def(
          "node_forces",
          [](const TSnake& self, const py::object& contour) {
            return array_from_matrix(self.node_forces(contour_argument(contour)));
          },
          py::arg("contour"), "The force sum of the deformation step at each node, (N, 2).")
      .def_static(
          "outward_normals",
          [](const py::object& contour) {
            return array_from_matrix(TSnake::outward_normals(contour_argument(contour)));
          },
          py::arg("contour"), "Outward unit normals of a contour, (N, 2).")
      .def(
          "intensity",
          [](const TSnake& self, const py::object& point) {
            return self.intensity(matrix_from_array(point, "point", 1, 2, true).row(0).transpose());
          },
          py::arg("point"), "The image intensity at (x, y), bilinear.")
      .def_property_readonly(
          "contours", [](const TSnake& self) { return contour_arrays(self.contours()); },
          "The snakes: a list of (N_i, 2) arrays (outer boundaries counter-clockwise).")
      .def_property_readonly("steps_taken", &TSnake::steps_taken, "Steps so far.")
      .def_property_readonly("enclosed_area", &TSnake::enclosed_area,
                             "The area of the inside region.");
  py::class_<TSurface>(module, "TSurface",
                       "A topology-adaptive surface in a Volume (McInerney & Terzopoulos): the "
                       "closed mesh of the inside region of a tetrahedral grid.")
      .def(py::init([](const Volume& volume, double sigma, double c, const py::kwargs& options) {
             return TSurface(volume, VolumeEdgePotential(volume, sigma, c),
                             adaptive_parameters<TSurfaceParameters>(options));
           }),
           py::arg("volume"), py::arg("sigma") = 1.0, py::arg("c") = 1.0,
           "The edge potential of `volume`; keyword parameters as TSnake (voxel units).")
      .def(
          "add_sphere",
          [](TSurface& self, const py::object& center, double radius) {
            self.add_sphere(vector3_argument(center, "center"), radius);
          },
          py::arg("center"), py::arg("radius"), "Adds a ball (x, y, z) in voxels.")
      .def("step", &TSurface::step, "One deformation step; True if the inside region changed.")
      .def("run", &TSurface::run, py::arg("max_steps"), py::arg("stable_steps") = 30,
           "Steps until stable; returns the steps taken.")
      .def(
          "vertex_forces",
          [](const TSurface& self) { return array_from_matrix(self.vertex_forces()); },
          "The force sum of the step at every mesh vertex, (V, 3).")
      .def(
          "intensity",
          [](const TSurface& self, const py::object& point) {
            return self.intensity(vector3_argument(point, "point"));
          },
          py::arg("point"), "The volume intensity at (x, y, z), trilinear.")
      .def_property_readonly("mesh", &TSurface::mesh, "The surface as a TriangleMesh.");
}

void bind_image_forces(py::module_& module) {
  module.def(
      "image_potential",
      [](const py::object& pixels, double sigma, double c) {
        const Potential potential =
            image_potential(matrix_from_array(pixels, "pixels", -1, -1), sigma, c);
        return py::cpp_function(
            [potential](double x, double y) { return potential(Eigen::Vector2d(x, y)); },
            py::arg("x"), py::arg("y"));
      },
      py::arg("pixels"), py::arg("sigma"), py::arg("c") = 1.0,
      "The snake potential P(x, y) = -c |grad(G_sigma * I)| of pixels (height, width) "
      "(Terzopoulos, below eq. 1.3), as ImageEdgePotential: a function of (x, y) in pixels.");
  module.def(
      "add_image_force",
      [](System& system, int model, const py::object& pixels, double sigma, double c,
         double gradient_step) {
        return system.add_force(
            model,
            potential_force(image_potential(matrix_from_array(pixels, "pixels", -1, -1), sigma, c),
                            gradient_step));
      },
      py::arg("system"), py::arg("model"), py::arg("pixels"), py::arg("sigma"), py::arg("c") = 1.0,
      py::arg("gradient_step") = 1e-6,
      "Adds the image force -grad P (eq. 1.5) at every node's (x, y) of a snake or grid "
      "surface `model` of `system`; returns the force's index.");
  const auto frame = [](const py::object& origin, const py::object& pixel_size) {
    ImageFrame result{vector3_argument(origin, "origin"), Eigen::Vector3d::Ones()};
    result.spacing = py::isinstance<py::float_>(pixel_size) || py::isinstance<py::int_>(pixel_size)
                         ? Eigen::Vector3d::Constant(py::cast<double>(pixel_size))
                         : vector3_argument(pixel_size, "pixel_size");
    return result;
  };
  module.def(
      "add_edge_force",
      [frame](System& system, int model, const ImageEdgePotential& potential,
              const py::object& origin, const py::object& pixel_size) {
        return system.add_force(
            model, image_edge_force(std::make_shared<const ImageEdgePotential>(potential),
                                    frame(origin, pixel_size)));
      },
      py::arg("system"), py::arg("model"), py::arg("potential"),
      py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0), py::arg("pixel_size") = 1.0,
      "Adds the edge force -grad P (eq. 1.5; the exact gradient of the interpolant) of an "
      "ImageEdgePotential to any model of `system`, the image placed with pixel (x, y) at "
      "origin + pixel_size * (x, y, 0) (pixel_size a number or (sx, sy, sz)); snakes and grid "
      "surfaces take it per node, the other models per unit parametric measure. Returns the "
      "force's index.");
  module.def(
      "add_edge_force",
      [frame](System& system, int model, const VolumeEdgePotential& potential,
              const py::object& origin, const py::object& pixel_size) {
        return system.add_force(
            model, volume_edge_force(std::make_shared<const VolumeEdgePotential>(potential),
                                     frame(origin, pixel_size)));
      },
      py::arg("system"), py::arg("model"), py::arg("potential"),
      py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0), py::arg("pixel_size") = 1.0,
      "The same for a VolumeEdgePotential: voxel (x, y, z) at origin + pixel_size * (x, y, z).");
}

// The parameters of Kalman snakes and their edge search from keyword arguments; Error naming an
// unknown key.
KalmanSnakeParameters kalman_parameters(const py::kwargs& options) {
  KalmanSnakeParameters parameters;
  for (const auto& [key, value] : options) {
    const auto name = py::cast<std::string>(key);
    double* field = name == "mass"                        ? &parameters.mass
                    : name == "damping"                   ? &parameters.damping
                    : name == "tension"                   ? &parameters.tension
                    : name == "rigidity"                  ? &parameters.rigidity
                    : name == "time_step"                 ? &parameters.time_step
                    : name == "acceleration_variance"     ? &parameters.acceleration_variance
                    : name == "initial_position_variance" ? &parameters.initial_position_variance
                    : name == "initial_velocity_variance" ? &parameters.initial_velocity_variance
                                                          : nullptr;
    if (field == nullptr) {
      throw make_error("unknown parameter \"", name,
                       "\" (mass, damping, tension, rigidity, time_step, acceleration_variance, "
                       "initial_position_variance, initial_velocity_variance)");
    }
    *field = py::cast<double>(value);
  }
  return parameters;
}

EdgeSearchParameters edge_search(const Image& frame, const py::kwargs& options) {
  EdgeSearchParameters search;
  search.width = frame.width();
  search.height = frame.height();
  for (const auto& [key, value] : options) {
    const auto name = py::cast<std::string>(key);
    if (name == "width" || name == "height") {
      (name == "width" ? search.width : search.height) = py::cast<int>(value);
      continue;
    }
    double* field = name == "sigma"               ? &search.sigma
                    : name == "half_window"       ? &search.half_window
                    : name == "sample_step"       ? &search.sample_step
                    : name == "min_edge_strength" ? &search.min_edge_strength
                    : name == "variance"          ? &search.variance
                                                  : nullptr;
    if (field == nullptr) {
      throw make_error("unknown edge search parameter \"", name,
                       "\" (width, height, sigma, half_window, sample_step, min_edge_strength, "
                       "variance)");
    }
    *field = py::cast<double>(value);
  }
  return search;
}

void bind_kalman_snake(py::module_& module) {
  py::class_<KalmanSnake>(
      module, "KalmanSnake",
      "A closed snake of N >= 3 nodes tracked by a Kalman filter (Terzopoulos & Szeliski 1992): "
      "the system model is the snake's step (eq 1.13) with white acceleration noise, the state "
      "(4N) [u_x, v_x, u_y, v_y] of node positions u and velocities v in pixel units.")
      .def(py::init([](const py::object& rest_shape, const py::object& initial_positions,
                       const py::object& initial_velocities, const py::kwargs& options) {
             const Contour rest = matrix_from_array(rest_shape, "rest_shape", -1, 2);
             const Contour start =
                 initial_positions.is_none()
                     ? rest
                     : Contour(matrix_from_array(initial_positions, "initial_positions", -1, 2));
             const Eigen::MatrixX2d velocity =
                 initial_velocities.is_none()
                     ? Eigen::MatrixX2d(Eigen::MatrixX2d::Zero(rest.rows(), 2))
                     : Eigen::MatrixX2d(
                           matrix_from_array(initial_velocities, "initial_velocities", -1, 2));
             return KalmanSnake(rest, start, velocity, kalman_parameters(options));
           }),
           py::arg("rest_shape"), py::arg("initial_positions") = py::none(),
           py::arg("initial_velocities") = py::none(),
           "rest_shape (N, 2); initial positions (N, 2) (default the rest shape) and velocities "
           "(N, 2) (default 0); keyword parameters mass, damping, tension, rigidity, time_step, "
           "acceleration_variance, initial_position_variance, initial_velocity_variance.")
      .def("predict", &KalmanSnake::predict, "The prediction x <- A x + b, P <- A P A^T + Q.")
      .def(
          "update",
          [](KalmanSnake& self, const py::object& measured, double variance) {
            self.update(Contour(matrix_from_array(measured, "measured_positions", -1, 2)),
                        variance);
          },
          py::arg("measured_positions"), py::arg("variance"),
          "The update with every node's position measured, (N, 2), noise variance per "
          "coordinate.")
      .def(
          "update_normals",
          [](KalmanSnake& self, const std::vector<int>& nodes, const py::object& normals,
             const py::object& positions, const py::object& variances) {
            const Eigen::MatrixXd n = matrix_from_array(normals, "normals", -1, 2);
            const auto count = static_cast<long>(nodes.size());
            if (n.rows() != count) {
              throw make_error("normals has ", n.rows(), " rows for ", count, " nodes");
            }
            const Eigen::VectorXd z = vector_from_array(positions, "positions", count);
            const Eigen::VectorXd r = vector_from_array(variances, "variances", count);
            std::vector<NormalMeasurement> measurements;
            for (long j = 0; j < count; ++j) {
              measurements.push_back(
                  {nodes[static_cast<std::size_t>(j)], n.row(j).transpose(), z[j], r[j]});
            }
            self.update(measurements);
          },
          py::arg("nodes"), py::arg("normals"), py::arg("positions"), py::arg("variances"),
          "The update with scalar measurements z_j = normals[j] . u_nodes[j]: nodes (M), unit "
          "normals (M, 2), positions (M), variances (M).")
      .def(
          "track",
          [](KalmanSnake& self, const Image& frame, const py::kwargs& options) {
            return self.track(frame, edge_search(frame, options));
          },
          py::arg("frame"),
          "Predict, search the frame along the predicted normals for the strongest edge of "
          "-|grad(G_sigma * I)| and update; returns the number of nodes that found one. "
          "Keyword parameters width, height (default the frame's), sigma, half_window, "
          "sample_step, min_edge_strength, variance.")
      .def_property_readonly(
          "positions", [](const KalmanSnake& self) { return array_from_matrix(self.positions()); },
          "The node positions, (N, 2).")
      .def_property_readonly(
          "velocities",
          [](const KalmanSnake& self) { return array_from_matrix(self.velocities()); },
          "The node velocities, (N, 2).")
      .def_property_readonly(
          "covariance",
          [](const KalmanSnake& self) { return array_from_matrix(self.covariance()); },
          "The state covariance, (4N, 4N).")
      .def(
          "node_covariance",
          [](const KalmanSnake& self, int i) { return array_from_matrix(self.node_covariance(i)); },
          py::arg("i"), "The covariance of node i's position, (2, 2).")
      .def_property_readonly("axes_separable", &KalmanSnake::axes_separable,
                             "True while the covariance is I_2 (x) P_s (no normal measurement).");
}

}  // namespace

void bind_vision(py::module_& module) {
  bind_images(module);
  bind_t_snakes(module);
  bind_kalman_snake(module);
  bind_image_forces(module);
}

}  // namespace dnurbs::python
