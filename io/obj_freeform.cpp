#include "dnurbs/io/obj_freeform.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <variant>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/nurbs/periodic_form.h"

namespace dnurbs {
namespace {

/// Relative tolerance of a curv/surf parameter range against the knot vector's domain.
constexpr double kRangeTolerance = 1e-12;

constexpr std::string_view kBlanks = " \t\r\v\f";

std::string_view trimmed(std::string_view text) {
  const std::size_t start = text.find_first_not_of(kBlanks);
  if (start == std::string_view::npos) {
    return {};
  }
  return text.substr(start, text.find_last_not_of(kBlanks) - start + 1);
}

/// The blank-separated tokens of `text`, at most `limit` of them.
std::vector<std::string_view> tokens(std::string_view text, std::size_t limit) {
  std::vector<std::string_view> result;
  for (std::size_t start = text.find_first_not_of(kBlanks);
       start != std::string_view::npos && result.size() < limit;
       start = text.find_first_not_of(kBlanks, start)) {
    const std::size_t end = std::min(text.find_first_of(kBlanks, start), text.size());
    result.push_back(text.substr(start, end - start));
    start = end;
  }
  return result;
}

/// The statements of OBJ text, one at a time: '#' starts a comment that runs to the end of the
/// line, and a line ending in a backslash continues on the next one (the Appendix B1 examples
/// break long curv and parm statements so). Blank lines are skipped.
class StatementReader {
 public:
  explicit StatementReader(std::string_view text) : text_(text) {}

  /// Moves to the next statement; false at the end of the text.
  bool next() {
    statement_.clear();
    while (position_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', position_), text_.size());
      std::string_view line = text_.substr(position_, end - position_);
      position_ = end + 1;
      ++physical_line_;
      line = trimmed(line.substr(0, line.find('#')));
      const bool continued = !line.empty() && line.back() == '\\';
      if (continued) {
        line.remove_suffix(1);
      }
      if (!line.empty()) {  // starts with a non-blank: the statement has begun
        line_ = statement_.empty() ? physical_line_ : line_;
        statement_.append(line).push_back(' ');
      }
      if (!continued && !statement_.empty()) {
        break;
      }
    }
    if (statement_.empty()) {
      return false;
    }
    const std::size_t keyword_end = statement_.find_first_of(kBlanks);  // the appended ' ' at least
    keyword_ = std::string_view(statement_).substr(0, keyword_end);
    arguments_ = trimmed(std::string_view(statement_).substr(keyword_end));
    return true;
  }

  /// The line the statement starts on (1-based).
  int line() const { return line_; }
  std::string_view keyword() const { return keyword_; }
  /// Everything after the keyword, without leading and trailing blanks.
  std::string_view arguments() const { return arguments_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  int physical_line_ = 0;
  int line_ = 0;
  std::string statement_;
  std::string_view keyword_;
  std::string_view arguments_;
};

/// A curv or surf statement with the body statements read so far.
struct Element {
  bool surface = false;
  int line = 0;
  bool rational = false;
  std::vector<int> degrees;                  // p, or p and q
  std::vector<double> range;                 // u0 u1, or s0 s1 t0 t1
  std::vector<int> vertices;                 // 0-based indices of v lines, in the statement's order
  std::array<std::vector<double>, 2> knots;  // parm u, parm v
  std::array<int, 2> knot_lines{};           // their lines, 0 before they are read

  const char* name() const { return surface ? "surf" : "curv"; }
};

class ObjReader {
 public:
  explicit ObjReader(std::string source) : source_(std::move(source)) {}

  std::vector<Shape> read(std::string_view text) {
    StatementReader reader(text);
    while (reader.next()) {
      line_ = reader.line();
      statement(reader.keyword(), reader.arguments());
    }
    if (element_) {
      fail(element_->line, element_->name(), " has no end statement");
    }
    return std::move(shapes_);
  }

 private:
  template <typename... Parts>
  [[noreturn]] void fail(int line, const Parts&... parts) const {
    throw make_error(source_, ": line ", line, ": ", parts...);
  }

  void statement(std::string_view keyword, std::string_view arguments) {
    if (keyword == "v") {
      read_vertex(arguments);
    } else if (keyword == "cstype") {
      read_cstype(arguments);
    } else if (keyword == "deg") {
      read_deg(arguments);
    } else if (keyword == "curv" || keyword == "surf") {
      read_element(keyword == "surf", arguments);
    } else if (keyword == "curv2") {
      fail(line_, "curv2 (2-D curves in a surface's parameter space) is not supported");
    } else if (!element_) {
      return;  // polygonal geometry, grouping, display attributes, and body statements outside a
               // block, which "do not have any effect" (Appendix B1)
    } else if (keyword == "parm") {
      read_parm(arguments);
    } else if (keyword == "trim" || keyword == "hole" || keyword == "scrv" || keyword == "sp") {
      fail(line_, "trimmed surfaces are not supported (a ", keyword, " statement in the ",
           element_->name(), " of line ", element_->line, ")");
    } else if (keyword == "end") {
      shapes_.push_back(element_->surface ? Shape(make_surface(*element_))
                                          : Shape(make_curve(*element_)));
      element_.reset();
    }
  }

  double number(std::string_view token) const {
    const std::string_view digits =
        token.size() > 1 && token[0] == '+' && token[1] != '-' ? token.substr(1) : token;
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (end != digits.data() + digits.size()) {
      fail(line_, "expected a number, got \"", printable_excerpt(token), "\"");
    }
    if (error == std::errc::result_out_of_range) {
      fail(line_, "the number ", printable_excerpt(token), " is out of the range of doubles");
    }
    if (!std::isfinite(value)) {
      fail(line_, "expected a finite number, got ", printable_excerpt(token));
    }
    return value;
  }

  long long integer(std::string_view token, const char* what) const {
    long long value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size()) {
      fail(line_, "expected ", what, ", got \"", printable_excerpt(token), "\"");
    }
    return value;
  }

  // v x y z [w], or x y z r g b (the vertex colour extension)
  void read_vertex(std::string_view arguments) {
    const std::vector<std::string_view> values = tokens(arguments, 7);
    if (values.size() != 3 && values.size() != 4 && values.size() != 6) {
      fail(line_, "expected v x y z [w], got \"v ", printable_excerpt(arguments), "\"");
    }
    std::array<double, 4> vertex = {number(values[0]), number(values[1]), number(values[2]), 1.0};
    if (values.size() == 4) {
      vertex[3] = number(values[3]);
      if (!(vertex[3] > 0.0)) {
        fail(line_, "expected a weight w > 0, got ", vertex[3]);
      }
    }
    vertices_.push_back(vertex);
  }

  void read_cstype(std::string_view arguments) {
    const std::vector<std::string_view> words = tokens(arguments, 3);
    const bool rational = !words.empty() && words[0] == "rat";
    const std::string_view type = words.size() == (rational ? 2U : 1U) ? words.back() : "";
    if (type == "bspline") {
      rational_ = rational;
      return;
    }
    if (type == "bezier" || type == "cardinal" || type == "taylor" || type == "bmatrix") {
      fail(line_, "cstype ", type, " is not supported (only bspline and rat bspline)");
    }
    fail(line_, "unknown cstype \"", printable_excerpt(arguments),
         "\" (expected bspline or rat bspline)");
  }

  void read_deg(std::string_view arguments) {
    const std::vector<std::string_view> values = tokens(arguments, 3);
    if (values.empty() || values.size() > 2) {
      fail(line_, "expected deg p or deg p q, got \"deg ", printable_excerpt(arguments), "\"");
    }
    degrees_.clear();
    for (const std::string_view value : values) {
      const long long degree = integer(value, "an integer degree");
      if (degree < 1 || degree > kMaxDegree) {
        fail(line_, "expected a degree in 1..", kMaxDegree, ", got ", degree);
      }
      degrees_.push_back(static_cast<int>(degree));
    }
  }

  // The 0-based index of vertex reference v, v/vt, v//vn or v/vt/vn; -1 is the last v line.
  int vertex_index(std::string_view token) const {
    const long long count = static_cast<long long>(vertices_.size());
    long long index = integer(token.substr(0, token.find('/')), "a vertex index");
    index += index < 0 ? count : -1;
    if (index < 0 || index >= count) {
      fail(line_, "vertex index ", printable_excerpt(token), " is out of range (", count,
           " v statements before it)");
    }
    return static_cast<int>(index);
  }

  // curv u0 u1 v1 v2 ... or surf s0 s1 t0 t1 v1 v2 ...
  void read_element(bool is_surface, std::string_view arguments) {
    Element element;
    element.surface = is_surface;
    element.line = line_;
    if (element_) {
      fail(element_->line, element_->name(), " has no end statement (line ", line_, " starts a ",
           element.name(), ")");
    }
    if (!rational_) {
      fail(line_, element.name(), " without a cstype statement before it");
    }
    const std::size_t directions = is_surface ? 2 : 1;
    if (degrees_.size() < directions) {
      fail(line_, element.name(), " without a deg statement before it",
           is_surface ? " that gives two degrees (deg p q)" : "");
    }
    const std::size_t range_count = 2 * directions;
    const std::vector<std::string_view> values = tokens(arguments, range_count + kObjMaxValues + 1);
    if (values.size() > range_count + kObjMaxValues) {
      fail(line_, element.name(), " has more than ", kObjMaxValues, " vertices (the limit)");
    }
    if (values.size() < range_count + 2) {
      fail(line_, "expected ", element.name(), is_surface ? " s0 s1 t0 t1" : " u0 u1",
           " and at least two vertices, got \"", element.name(), " ", printable_excerpt(arguments),
           "\"");
    }
    element.rational = *rational_;
    element.degrees.assign(degrees_.begin(), degrees_.begin() + static_cast<int>(directions));
    for (std::size_t k = 0; k < range_count; ++k) {
      element.range.push_back(number(values[k]));
    }
    element.vertices.reserve(values.size() - range_count);
    for (std::size_t k = range_count; k < values.size(); ++k) {
      element.vertices.push_back(vertex_index(values[k]));
    }
    element_ = std::move(element);
  }

  // parm u t0 t1 ... or parm v t0 t1 ... (the whole knot vector)
  void read_parm(std::string_view arguments) {
    const std::vector<std::string_view> values = tokens(arguments, kObjMaxValues + 2);
    const std::size_t direction = !values.empty() && values[0] == "v" ? 1 : 0;
    if (values.empty() || (values[0] != "u" && (values[0] != "v" || !element_->surface))) {
      fail(line_, "expected parm u", element_->surface ? " or parm v" : "", " in a ",
           element_->name(), ", got \"parm ", printable_excerpt(arguments), "\"");
    }
    if (element_->knot_lines[direction] != 0) {
      fail(line_, "a second parm ", values[0], " (the first is on line ",
           element_->knot_lines[direction], ")");
    }
    if (values.size() > kObjMaxValues + 1) {
      fail(line_, "parm ", values[0], " has more than ", kObjMaxValues, " knots (the limit)");
    }
    std::vector<double>& knots = element_->knots[direction];
    knots.reserve(values.size() - 1);
    for (std::size_t k = 1; k < values.size(); ++k) {
      knots.push_back(number(values[k]));
    }
    element_->knot_lines[direction] = line_;
  }

  // The knot vector of parm u (direction 0) or parm v (1), whose domain must be the range the
  // curv or surf statement gives.
  KnotVector knot_vector(const Element& element, std::size_t direction) const {
    const char* parm = direction == 0 ? "parm u" : "parm v";
    if (element.knot_lines[direction] == 0) {
      fail(element.line, element.name(), " has no ", parm, " statement before its end");
    }
    std::optional<KnotVector> knots;
    try {
      knots.emplace(element.degrees[direction], element.knots[direction]);
    } catch (const Error& error) {
      fail(element.knot_lines[direction], "invalid knots in ", parm, ": ", error.what());
    }
    const double first = element.range[2 * direction];
    const double last = element.range[2 * direction + 1];
    const double start = knots->domain_start();
    const double end = knots->domain_end();
    const double tolerance =
        kRangeTolerance * std::max({std::abs(start), std::abs(end), end - start});
    if (std::abs(first - start) > tolerance || std::abs(last - end) > tolerance) {
      fail(element.line, element.name(), " parameter range ", first, " ", last,
           direction == 0 ? " in u" : " in v", " is not the domain ", start, " ", end, " of ", parm,
           ": trimming is not supported");
    }
    return *knots;
  }

  void set_control_point(const Element& element, std::size_t reference, Eigen::Index row,
                         Eigen::MatrixX3d& points, Eigen::VectorXd& weights) const {
    const std::array<double, 4>& vertex =
        vertices_[static_cast<std::size_t>(element.vertices[reference])];
    points.row(row) << vertex[0], vertex[1], vertex[2];
    weights(row) = element.rational ? vertex[3] : 1.0;
  }

  NurbsCurve make_curve(const Element& element) const {
    const std::size_t count = element.vertices.size();
    const std::size_t expected = count + static_cast<std::size_t>(element.degrees[0]) + 1;
    if (element.knot_lines[0] != 0 && element.knots[0].size() != expected) {
      fail(element.knot_lines[0], "parm u has ", element.knots[0].size(), " knots, expected ",
           expected, " (", count, " control points + degree ", element.degrees[0], " + 1)");
    }
    const KnotVector knots = knot_vector(element, 0);
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(count), 3);
    Eigen::VectorXd weights(static_cast<Eigen::Index>(count));
    for (std::size_t k = 0; k < count; ++k) {
      set_control_point(element, k, static_cast<Eigen::Index>(k), points, weights);
    }
    return periodic_form(NurbsCurve(knots, std::move(points), std::move(weights)));
  }

  NurbsSurface make_surface(const Element& element) const {
    const KnotVector knots_u = knot_vector(element, 0);
    const KnotVector knots_v = knot_vector(element, 1);
    const int count_u = knots_u.control_point_count();
    const int count_v = knots_v.control_point_count();
    const std::size_t count = element.vertices.size();
    if (static_cast<std::size_t>(count_u) * static_cast<std::size_t>(count_v) != count) {
      fail(element.line, "surf has ", count, " control vertices, but parm u (", knots_u.size(),
           " knots, degree ", element.degrees[0], ") and parm v (", knots_v.size(),
           " knots, degree ", element.degrees[1], ") give ", count_u, " x ", count_v,
           " (knots = control points + degree + 1 in each direction)");
    }
    Eigen::MatrixX3d points(count_u * count_v, 3);
    Eigen::VectorXd weights(count_u * count_v);
    // The file lists control point (i, j) at i + j n_u (u fastest); dnurbs at i n_v + j.
    for (int j = 0; j < count_v; ++j) {
      for (int i = 0; i < count_u; ++i) {
        set_control_point(element, static_cast<std::size_t>(i + j * count_u), i * count_v + j,
                          points, weights);
      }
    }
    return periodic_form(NurbsSurface(knots_u, knots_v, std::move(points), std::move(weights)));
  }

  std::string source_;
  int line_ = 0;
  std::vector<std::array<double, 4>> vertices_;  // x y z w of every v line so far
  std::optional<bool> rational_;                 // of the last cstype (none yet: nothing)
  std::vector<int> degrees_;                     // of the last deg
  std::optional<Element> element_;               // the curv or surf before its end
  std::vector<Shape> shapes_;
};

/// Appends a blank and the shortest text that reads back as exactly `value`.
void append_number(std::string& out, double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.push_back(' ');
  out.append(buffer.data(), result.ptr);
}

void append_vertex(std::string& out, const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
                   Eigen::Index row, bool rational) {
  out.push_back('v');
  for (int c = 0; c < 3; ++c) {
    append_number(out, points(row, c));
  }
  if (rational) {
    append_number(out, weights(row));
  }
  out.push_back('\n');
}

/// Appends the references to the `count` vertices after the first `vertex_count` ones and counts
/// them in.
void append_references(std::string& out, std::size_t count, std::size_t& vertex_count) {
  for (std::size_t k = 1; k <= count; ++k) {
    out.append(" ").append(std::to_string(vertex_count + k));
  }
  out.push_back('\n');
  vertex_count += count;
}

void append_knots(std::string& out, const char* parm, const KnotVector& knots) {
  out.append(parm);
  for (const double knot : knots.knots()) {
    append_number(out, knot);
  }
  out.push_back('\n');
}

void append_shape(std::string& out, const NurbsCurve& shape, std::size_t& vertex_count) {
  const NurbsCurve curve = open_form(shape);
  for (int i = 0; i < curve.control_point_count(); ++i) {
    append_vertex(out, curve.control_points(), curve.weights(), i, curve.is_rational());
  }
  out.append(curve.is_rational() ? "cstype rat bspline\n" : "cstype bspline\n");
  out.append("deg ").append(std::to_string(curve.degree())).append("\ncurv");
  append_number(out, curve.knots().domain_start());
  append_number(out, curve.knots().domain_end());
  append_references(out, static_cast<std::size_t>(curve.control_point_count()), vertex_count);
  append_knots(out, "parm u", curve.knots());
  out.append("end\n");
}

void append_shape(std::string& out, const NurbsSurface& shape, std::size_t& vertex_count) {
  const NurbsSurface surface = open_form(shape);
  for (int j = 0; j < surface.control_point_count_v(); ++j) {
    for (int i = 0; i < surface.control_point_count_u(); ++i) {  // u fastest
      append_vertex(out, surface.control_points(), surface.weights(),
                    surface.control_point_index(i, j), surface.is_rational());
    }
  }
  out.append(surface.is_rational() ? "cstype rat bspline\n" : "cstype bspline\n");
  out.append("deg ").append(std::to_string(surface.degree_u())).append(" ");
  out.append(std::to_string(surface.degree_v())).append("\nsurf");
  for (const KnotVector* knots : {&surface.knots_u(), &surface.knots_v()}) {
    append_number(out, knots->domain_start());
    append_number(out, knots->domain_end());
  }
  append_references(out, static_cast<std::size_t>(surface.control_point_count()), vertex_count);
  append_knots(out, "parm u", surface.knots_u());
  append_knots(out, "parm v", surface.knots_v());
  out.append("end\n");
}

}  // namespace

std::string shapes_to_obj(const std::vector<Shape>& shapes) {
  std::string out = "# NURBS curves and surfaces as OBJ free-form geometry, written by dnurbs\n";
  std::size_t vertex_count = 0;
  for (const Shape& shape : shapes) {
    std::visit([&](const auto& value) { append_shape(out, value, vertex_count); }, shape);
  }
  return out;
}

void write_obj_freeform_file(const std::filesystem::path& path, const std::vector<Shape>& shapes) {
  write_file_atomically(path, shapes_to_obj(shapes));
}

std::vector<Shape> parse_obj_freeform(const std::string& text, const std::string& source) {
  return ObjReader(source).read(text);
}

std::vector<Shape> read_obj_freeform_file(const std::filesystem::path& path) {
  return parse_obj_freeform(read_input_file(path, "OBJ file"), path.string());
}

bool has_obj_freeform(const std::string& text) {
  StatementReader reader(text);
  while (reader.next()) {
    if (reader.keyword() == "curv" || reader.keyword() == "surf") {
      return true;
    }
  }
  return false;
}

}  // namespace dnurbs
