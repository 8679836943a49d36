#include "dnurbs/nurbs/dunavant_rules.h"

#include <array>
#include <cmath>
#include <mutex>
#include <optional>
#include <vector>

#include <Eigen/QR>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// One degree of Dunavant's Table I, its orbits grouped by multiplicity (the order in which the
// table lists them and the rule's points follow): the weight of each point and the free
// barycentric coordinates of the point that generates the orbit, as the polishing iterates on.
struct RuleEntry {
  int degree;
  // The centroid (1/3, 1/3, 1/3), if the rule has it: its weight.
  std::optional<double> centroid;
  // (1 - 2a, a, a) and its 3 permutations: (weight, a), a = beta = gamma of the table.
  std::vector<std::array<double, 2>> orbits3;
  // (a, b, 1 - a - b) and its 6 permutations: (weight, a, b), (a, b) = (alpha, beta).
  std::vector<std::array<double, 3>> orbits6;
};

// Dunavant (1985), Table I, degrees 1..14 (15 digits as published).
const std::vector<RuleEntry>& dunavant_table() {
  static const std::vector<RuleEntry> table = {
      {1, 1.0, {}, {}},
      {2, std::nullopt, {{0.333333333333333, 0.166666666666667}}, {}},
      {3, -0.5625, {{0.520833333333333, 0.2}}, {}},
      {4,
       std::nullopt,
       {{0.223381589678011, 0.445948490915965}, {0.109951743655322, 0.091576213509771}},
       {}},
      {5,
       0.225,
       {{0.132394152788506, 0.470142064105115}, {0.125939180544827, 0.101286507323456}},
       {}},
      {6,
       std::nullopt,
       {{0.116786275726379, 0.249286745170910}, {0.050844906370207, 0.063089014491502}},
       {{0.082851075618374, 0.053145049844817, 0.310352451033784}}},
      {7,
       -0.149570044467682,
       {{0.175615257433208, 0.260345966079040}, {0.053347235608838, 0.065130102902216}},
       {{0.077113760890257, 0.048690315425316, 0.312865496004874}}},
      {8,
       0.144315607677787,
       {{0.095091634267285, 0.459292588292723},
        {0.103217370534718, 0.170569307751760},
        {0.032458497623198, 0.050547228317031}},
       {{0.027230314174435, 0.008394777409958, 0.263112829634638}}},
      {9,
       0.097135796282799,
       {{0.031334700227139, 0.489682519198738},
        {0.077827541004774, 0.437089591492937},
        {0.079647738927210, 0.188203535619033},
        {0.025577675658698, 0.044729513394453}},
       {{0.043283539377289, 0.036838412054736, 0.221962989160766}}},
      {10,
       0.090817990382754,
       {{0.036725957756467, 0.485577633383657}, {0.045321059435528, 0.109481575485037}},
       {{0.072757916845420, 0.141707219414880, 0.307939838764121},
        {0.028327242531057, 0.025003534762686, 0.246672560639903},
        {0.009421666963733, 0.009540815400299, 0.066803251012200}}},
      {11,
       std::nullopt,
       {{0.000927006328961, 0.534611048270758},
        {0.077149534914813, 0.398969302965855},
        {0.059322977380774, 0.203309900431282},
        {0.036184540503418, 0.119350912282581},
        {0.013659731002678, 0.032364948111276}},
       {{0.052337111962204, 0.050178138310495, 0.356620648261293},
        {0.020707659639141, 0.021022016536166, 0.171488980304042}}},
      {12,
       std::nullopt,
       {{0.025731066440455, 0.488217389773805},
        {0.043692544538038, 0.439724392294460},
        {0.062858224217885, 0.271210385012116},
        {0.034796112930709, 0.127576145541586},
        {0.006166261051559, 0.021317350453210}},
       {{0.040371557766381, 0.115343494534698, 0.275713269685514},
        {0.022356773202303, 0.022838332222257, 0.281325580989940},
        {0.017316231108659, 0.025734050548330, 0.116251915907597}}},
      {13,
       0.052520923400802,
       {{0.011280145209330, 0.495048184939705},
        {0.031423518362454, 0.468716635109574},
        {0.047072502504194, 0.414521336801277},
        {0.047363586536355, 0.229399572042831},
        {0.031167529045794, 0.114424495196330},
        {0.007975771465074, 0.024811391363459}},
       {{0.036848402728732, 0.094853828379579, 0.268794997058761},
        {0.017401463303822, 0.018100773278807, 0.291730066734288},
        {0.015521786839045, 0.022233076674090, 0.126357385491669}}},
      {14,
       std::nullopt,
       {{0.021883581369429, 0.488963910362179},
        {0.032788353544125, 0.417644719340454},
        {0.051774104507292, 0.273477528308839},
        {0.042162588736993, 0.177205532412543},
        {0.014433699669777, 0.061799883090873},
        {0.004923403602400, 0.019390961248701}},
       {{0.024665753212564, 0.057124757403648, 0.172266687821356},
        {0.038571510787061, 0.092916249356972, 0.336861459796345},
        {0.014436308113534, 0.014646950055654, 0.298372882136258},
        {0.005010228838501, 0.001268330932872, 0.118974497696957}}},
  };
  return table;
}

using Real = long double;
using RealVector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using RealMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

// The points (l1, l2, weight) of the rule with the orbits of `entry` at the parameters p: the
// centroid's weight (if the rule has it), then (weight, a) of each 3-point orbit, then
// (weight, a, b) of each 6-point orbit; the table's own values are not read.
std::vector<std::array<Real, 3>> expand(const RuleEntry& entry, const RealVector& p) {
  std::vector<std::array<Real, 3>> points;  // (l1, l2, weight)
  Eigen::Index k = 0;
  if (entry.centroid.has_value()) {
    points.push_back({Real(1) / 3, Real(1) / 3, p[k++]});
  }
  for (std::size_t orbit = 0; orbit < entry.orbits3.size(); ++orbit) {
    const Real w = p[k++];
    const Real a = p[k++];
    const Real c = 1 - 2 * a;
    points.push_back({a, a, w});
    points.push_back({c, a, w});
    points.push_back({a, c, w});
  }
  for (std::size_t orbit = 0; orbit < entry.orbits6.size(); ++orbit) {
    const Real w = p[k++];
    const Real a = p[k++];
    const Real b = p[k++];
    const Real c = 1 - a - b;
    const std::array<Real, 3> l = {a, b, c};
    const std::array<std::array<int, 3>, 6> order = {
        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (const auto& o : order) {
      points.push_back({l[static_cast<size_t>(o[1])], l[static_cast<size_t>(o[2])], w});
    }
  }
  return points;
}

// Moment residuals sum_g w_g x_g^i y_g^j - 2 i! j! / (i + j + 2)! on the reference triangle
// (x, y) = (l1, l2), for every i + j <= degree.
RealVector residuals(const RuleEntry& entry, const RealVector& p) {
  const int degree = entry.degree;
  const auto points = expand(entry, p);
  RealVector r((degree + 1) * (degree + 2) / 2);
  Eigen::Index row = 0;
  for (int i = 0; i <= degree; ++i) {
    for (int j = 0; i + j <= degree; ++j) {
      // 2 i! j! / (i + j + 2)! = 2 prod_k k / (j + k) / ((i + j + 1)(i + j + 2)).
      Real exact = 2;
      for (int k = 1; k <= i; ++k) {
        exact *= Real(k) / Real(j + k);
      }
      exact /= Real(i + j + 1) * Real(i + j + 2);
      Real sum = 0;
      for (const auto& point : points) {
        Real term = point[2];
        for (int k = 0; k < i; ++k) {
          term *= point[0];
        }
        for (int k = 0; k < j; ++k) {
          term *= point[1];
        }
        sum += term;
      }
      r[row++] = sum - exact;
    }
  }
  return r;
}

TriangleRule polished_rule(const RuleEntry& entry) {
  // Starting parameters from the table, in the order expand reads them.
  std::vector<Real> start;
  if (entry.centroid.has_value()) {
    start.push_back(*entry.centroid);
  }
  for (const auto& [weight, a] : entry.orbits3) {
    start.insert(start.end(), {weight, a});
  }
  for (const auto& [weight, a, b] : entry.orbits6) {
    start.insert(start.end(), {weight, a, b});
  }
  RealVector p = Eigen::Map<RealVector>(start.data(), static_cast<Eigen::Index>(start.size()));
  // Gauss-Newton on the (consistent, overdetermined) moment equations; the Jacobian by central
  // differences (step 1e-9: truncation ~1e-18, rounding ~1e-19 / 1e-9 = 1e-10 relative, so
  // each step gains about ten digits from the 15 of the table).
  for (int iteration = 0; iteration < 8; ++iteration) {
    const RealVector r = residuals(entry, p);
    if (r.cwiseAbs().maxCoeff() < Real(1e-18)) {
      break;
    }
    RealMatrix jacobian(r.size(), p.size());
    const Real step = Real(1e-9);
    for (Eigen::Index k = 0; k < p.size(); ++k) {
      RealVector plus = p;
      RealVector minus = p;
      plus[k] += step;
      minus[k] -= step;
      jacobian.col(k) = (residuals(entry, plus) - residuals(entry, minus)) / (2 * step);
    }
    p -= jacobian.colPivHouseholderQr().solve(r);
  }
  const auto points = expand(entry, p);
  TriangleRule rule;
  rule.degree = entry.degree;
  rule.barycentric.resize(static_cast<Eigen::Index>(points.size()), 3);
  rule.weights.resize(static_cast<Eigen::Index>(points.size()));
  for (size_t g = 0; g < points.size(); ++g) {
    const auto row = static_cast<Eigen::Index>(g);
    rule.barycentric(row, 1) = static_cast<double>(points[g][0]);
    rule.barycentric(row, 2) = static_cast<double>(points[g][1]);
    rule.barycentric(row, 0) = static_cast<double>(1 - points[g][0] - points[g][1]);
    rule.weights[row] = static_cast<double>(points[g][2]);
  }
  rule.interior_and_positive = rule.barycentric.minCoeff() >= 0.0 && rule.weights.minCoeff() > 0.0;
  return rule;
}

}  // namespace

const TriangleRule& dunavant_rule(int degree) {
  if (degree < 1 || degree > kMaxDunavantDegree) {
    throw make_error("Dunavant rule degree ", degree, " is outside 1..", kMaxDunavantDegree);
  }
  static std::array<TriangleRule, kMaxDunavantDegree + 1> rules;
  static std::array<std::once_flag, kMaxDunavantDegree + 1> once;
  const auto index = static_cast<size_t>(degree);
  std::call_once(once[index], [&] { rules[index] = polished_rule(dunavant_table()[index - 1]); });
  return rules[index];
}

const TriangleRule& interior_positive_dunavant_rule(int degree) {
  if (degree < 1 || degree > kMaxDunavantDegree) {
    throw make_error("quadrature degree ", degree, " is outside 1..", kMaxDunavantDegree);
  }
  for (int d = degree; d < kMaxDunavantDegree; ++d) {
    if (dunavant_rule(d).interior_and_positive) {
      return dunavant_rule(d);
    }
  }
  return dunavant_rule(kMaxDunavantDegree);
}

TriangleRule subdivided_rule(const TriangleRule& rule, int subdivisions) {
  if (subdivisions < 1 || subdivisions > 256) {
    throw make_error("triangle subdivisions ", subdivisions, " is outside 1..256");
  }
  const int s = subdivisions;
  TriangleRule result;
  result.degree = rule.degree;
  result.interior_and_positive = rule.interior_and_positive;
  const int count = rule.point_count();
  result.barycentric.resize(static_cast<Eigen::Index>(s) * s * count, 3);
  result.weights.resize(static_cast<Eigen::Index>(s) * s * count);
  Eigen::Index row = 0;
  // Sub-triangles of the lattice l = (i, j, k) / s: s (s + 1) / 2 upright ones with corners
  // (i + 1, j, k), (i, j + 1, k), (i, j, k + 1) for i + j + k = s - 1 and s (s - 1) / 2
  // inverted ones with corners (i, j + 1, k + 1), (i + 1, j, k + 1), (i + 1, j + 1, k) for
  // i + j + k = s - 2; each has area 1 / s^2 of the triangle.
  for (int inverted = 0; inverted < 2; ++inverted) {
    const int total = s - 1 - inverted;
    for (int i = 0; i <= total; ++i) {
      for (int j = 0; i + j <= total; ++j) {
        const Eigen::Vector3d base(i, j, total - i - j);
        std::array<Eigen::Vector3d, 3> corners;
        for (int c = 0; c < 3; ++c) {
          const Eigen::Vector3d step =
              inverted == 0 ? Eigen::Vector3d(Eigen::Vector3d::Unit(c))
                            : Eigen::Vector3d(Eigen::Vector3d::Ones() - Eigen::Vector3d::Unit(c));
          corners[static_cast<size_t>(c)] = base + step;
          corners[static_cast<size_t>(c)] /= s;
        }
        for (int g = 0; g < count; ++g, ++row) {
          result.barycentric.row(row) =
              (rule.barycentric(g, 0) * corners[0] + rule.barycentric(g, 1) * corners[1] +
               rule.barycentric(g, 2) * corners[2])
                  .transpose();
          result.weights[row] = rule.weights[g] / (s * s);
        }
      }
    }
  }
  return result;
}

}  // namespace dnurbs
