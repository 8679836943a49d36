#include "nurbs/dunavant_rules.h"

#include <array>
#include <cmath>
#include <mutex>
#include <vector>

#include <Eigen/QR>

#include "core/error.h"

namespace dnurbs {

namespace {

// One orbit of Dunavant's Table I: barycentric coordinates of one point (the orbit is all its
// distinct permutations: 1, 3 or 6 points) and the weight of each point.
struct OrbitEntry {
  double l0, l1, l2, weight;
};

struct RuleEntry {
  int degree;
  std::vector<OrbitEntry> orbits;
};

// Dunavant (1985), Table I, degrees 1..14 (15 digits as published).
const std::vector<RuleEntry>& dunavant_table() {
  static const std::vector<RuleEntry> table = {
      {1, {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 1.0}}},
      {2, {{0.666666666666667, 0.166666666666667, 0.166666666666667, 0.333333333333333}}},
      {3, {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, -0.5625}, {0.6, 0.2, 0.2, 0.520833333333333}}},
      {4,
       {{0.108103018168070, 0.445948490915965, 0.445948490915965, 0.223381589678011},
        {0.816847572980459, 0.091576213509771, 0.091576213509771, 0.109951743655322}}},
      {5,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.225},
        {0.059715871789770, 0.470142064105115, 0.470142064105115, 0.132394152788506},
        {0.797426985353087, 0.101286507323456, 0.101286507323456, 0.125939180544827}}},
      {6,
       {{0.501426509658179, 0.249286745170910, 0.249286745170910, 0.116786275726379},
        {0.873821971016996, 0.063089014491502, 0.063089014491502, 0.050844906370207},
        {0.053145049844817, 0.310352451033784, 0.636502499121399, 0.082851075618374}}},
      {7,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, -0.149570044467682},
        {0.479308067841920, 0.260345966079040, 0.260345966079040, 0.175615257433208},
        {0.869739794195568, 0.065130102902216, 0.065130102902216, 0.053347235608838},
        {0.048690315425316, 0.312865496004874, 0.638444188569810, 0.077113760890257}}},
      {8,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.144315607677787},
        {0.081414823414554, 0.459292588292723, 0.459292588292723, 0.095091634267285},
        {0.658861384496480, 0.170569307751760, 0.170569307751760, 0.103217370534718},
        {0.898905543365938, 0.050547228317031, 0.050547228317031, 0.032458497623198},
        {0.008394777409958, 0.263112829634638, 0.728492392955404, 0.027230314174435}}},
      {9,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.097135796282799},
        {0.020634961602525, 0.489682519198738, 0.489682519198738, 0.031334700227139},
        {0.125820817014127, 0.437089591492937, 0.437089591492937, 0.077827541004774},
        {0.623592928761935, 0.188203535619033, 0.188203535619033, 0.079647738927210},
        {0.910540973211095, 0.044729513394453, 0.044729513394453, 0.025577675658698},
        {0.036838412054736, 0.221962989160766, 0.741198598784498, 0.043283539377289}}},
      {10,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.090817990382754},
        {0.028844733232685, 0.485577633383657, 0.485577633383657, 0.036725957756467},
        {0.781036849029926, 0.109481575485037, 0.109481575485037, 0.045321059435528},
        {0.141707219414880, 0.307939838764121, 0.550352941820999, 0.072757916845420},
        {0.025003534762686, 0.246672560639903, 0.728323904597411, 0.028327242531057},
        {0.009540815400299, 0.066803251012200, 0.923655933587500, 0.009421666963733}}},
      {11,
       {{-0.069222096541517, 0.534611048270758, 0.534611048270758, 0.000927006328961},
        {0.202061394068290, 0.398969302965855, 0.398969302965855, 0.077149534914813},
        {0.593380199137435, 0.203309900431282, 0.203309900431282, 0.059322977380774},
        {0.761298175434837, 0.119350912282581, 0.119350912282581, 0.036184540503418},
        {0.935270103777448, 0.032364948111276, 0.032364948111276, 0.013659731002678},
        {0.050178138310495, 0.356620648261293, 0.593201213428213, 0.052337111962204},
        {0.021022016536166, 0.171488980304042, 0.807489003159792, 0.020707659639141}}},
      {12,
       {{0.023565220452390, 0.488217389773805, 0.488217389773805, 0.025731066440455},
        {0.120551215411079, 0.439724392294460, 0.439724392294460, 0.043692544538038},
        {0.457579229975768, 0.271210385012116, 0.271210385012116, 0.062858224217885},
        {0.744847708916828, 0.127576145541586, 0.127576145541586, 0.034796112930709},
        {0.957365299093579, 0.021317350453210, 0.021317350453210, 0.006166261051559},
        {0.115343494534698, 0.275713269685514, 0.608943235779788, 0.040371557766381},
        {0.022838332222257, 0.281325580989940, 0.695836086787803, 0.022356773202303},
        {0.025734050548330, 0.116251915907597, 0.858014033544073, 0.017316231108659}}},
      {13,
       {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.052520923400802},
        {0.009903630120591, 0.495048184939705, 0.495048184939705, 0.011280145209330},
        {0.062566729780852, 0.468716635109574, 0.468716635109574, 0.031423518362454},
        {0.170957326397447, 0.414521336801277, 0.414521336801277, 0.047072502504194},
        {0.541200855914337, 0.229399572042831, 0.229399572042831, 0.047363586536355},
        {0.771151009607340, 0.114424495196330, 0.114424495196330, 0.031167529045794},
        {0.950377217273082, 0.024811391363459, 0.024811391363459, 0.007975771465074},
        {0.094853828379579, 0.268794997058761, 0.636351174561660, 0.036848402728732},
        {0.018100773278807, 0.291730066734288, 0.690169159986905, 0.017401463303822},
        {0.022233076674090, 0.126357385491669, 0.851409537834241, 0.015521786839045}}},
      {14,
       {{0.022072179275643, 0.488963910362179, 0.488963910362179, 0.021883581369429},
        {0.164710561319092, 0.417644719340454, 0.417644719340454, 0.032788353544125},
        {0.453044943382323, 0.273477528308839, 0.273477528308839, 0.051774104507292},
        {0.645588935174913, 0.177205532412543, 0.177205532412543, 0.042162588736993},
        {0.876400233818255, 0.061799883090873, 0.061799883090873, 0.014433699669777},
        {0.961218077502598, 0.019390961248701, 0.019390961248701, 0.004923403602400},
        {0.057124757403648, 0.172266687821356, 0.770608554774996, 0.024665753212564},
        {0.092916249356972, 0.336861459796345, 0.570222290846683, 0.038571510787061},
        {0.014646950055654, 0.298372882136258, 0.686980167808088, 0.014436308113534},
        {0.001268330932872, 0.118974497696957, 0.879757171370171, 0.005010228838501}}},
  };
  return table;
}

using Real = long double;
using RealVector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using RealMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

// An orbit in polishing form: kind 1 (centroid; no position parameter), 3 ((1 - 2a, a, a) and
// permutations; parameter a) or 6 ((a, b, 1 - a - b) and permutations; parameters a, b).
struct Orbit {
  int kind = 1;
};

// Parameters: per orbit its weight, then a (kinds 3, 6), then b (kind 6).
std::vector<std::array<Real, 3>> expand(const std::vector<Orbit>& orbits, const RealVector& p) {
  std::vector<std::array<Real, 3>> points;  // (l1, l2, weight)
  Eigen::Index k = 0;
  for (const Orbit& orbit : orbits) {
    const Real w = p[k++];
    if (orbit.kind == 1) {
      points.push_back({Real(1) / 3, Real(1) / 3, w});
    } else if (orbit.kind == 3) {
      const Real a = p[k++];
      const Real c = 1 - 2 * a;
      points.push_back({a, a, w});
      points.push_back({c, a, w});
      points.push_back({a, c, w});
    } else {
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
  }
  return points;
}

// Moment residuals sum_g w_g x_g^i y_g^j - 2 i! j! / (i + j + 2)! on the reference triangle
// (x, y) = (l1, l2), for every i + j <= degree.
RealVector residuals(const std::vector<Orbit>& orbits, const RealVector& p, int degree) {
  const auto points = expand(orbits, p);
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
  // Orbit structure and starting parameters from the table.
  std::vector<Orbit> orbits;
  std::vector<Real> start;
  for (const OrbitEntry& o : entry.orbits) {
    start.push_back(o.weight);
    if (o.l0 == o.l1 && o.l1 == o.l2) {
      orbits.push_back({1});
    } else if (o.l1 == o.l2) {
      orbits.push_back({3});
      start.push_back(o.l1);
    } else {
      orbits.push_back({6});
      start.push_back(o.l0);
      start.push_back(o.l1);
    }
  }
  RealVector p = Eigen::Map<RealVector>(start.data(), static_cast<Eigen::Index>(start.size()));
  // Gauss-Newton on the (consistent, overdetermined) moment equations; the Jacobian by central
  // differences (step 1e-9: truncation ~1e-18, rounding ~1e-19 / 1e-9 = 1e-10 relative, so
  // each step gains about ten digits from the 15 of the table).
  for (int iteration = 0; iteration < 8; ++iteration) {
    const RealVector r = residuals(orbits, p, entry.degree);
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
      jacobian.col(k) =
          (residuals(orbits, plus, entry.degree) - residuals(orbits, minus, entry.degree)) /
          (2 * step);
    }
    p -= jacobian.colPivHouseholderQr().solve(r);
  }
  const auto points = expand(orbits, p);
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
