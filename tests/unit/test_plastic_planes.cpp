// Elastic-plastic PLANE182 / PLANE183 (src/elements/plane_solid_plastic.cpp): every stiffness
// point of a distorted element under a homogeneous strain history equals the material point
// (every shape, technology and behaviour), the element tangent against finite differences, the
// restart state round trip, uniaxial stretches through decks against the bilinear closed form
// (plane stress; axial stress in axisymmetry) and the plane-strain limit 2σy/√3, distorted-mesh
// patch tests in the plastic range, and creep through the element at constant load against the
// time-hardening closed form.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "../support/run_deck.h"
#include "elements/plane_solid.h"
#include "materials/j2_plasticity.h"

namespace impactfe::test_plastic_planes {
namespace {

constexpr double kE = 200e3, kNu = 0.3, kSy = 250.0, kEt = 20e3;

struct Variant {
  PlaneShape shape;
  PlaneTechnology technology;
  PlaneBehaviour behaviour;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (PlaneBehaviour b :
       {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain, PlaneBehaviour::Axisymmetric}) {
    out.push_back({PlaneShape::Quad4, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Quad4, PlaneTechnology::IncompatibleModes, b});
    out.push_back({PlaneShape::Quad4, PlaneTechnology::Reduced, b});
    if (b != PlaneBehaviour::PlaneStress)
      out.push_back({PlaneShape::Quad4, PlaneTechnology::BBar, b});
    out.push_back({PlaneShape::Quad8, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Tri3, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Tri6, PlaneTechnology::Standard, b});
  }
  return out;
}

std::string name(const Variant& v) {
  return fmt::format("shape {} technology {} behaviour {}", static_cast<int>(v.shape),
                     static_cast<int>(v.technology), static_cast<int>(v.behaviour));
}

/// A smooth distortion of the plane (curved edges for the quadratic shapes), at X >= 1.
Vec3 distort(double s, double t) {
  return Vec3(2.0 + 1.0 * s + 0.15 * s * t + 0.05 * (1 - t * t),
              0.5 + 0.8 * t + 0.1 * s + 0.06 * (1 - s * s) * t, 0.0);
}

struct Single {
  std::unique_ptr<PlaneSolid> element;
  std::vector<Vec3> x;
};

Single single(const Variant& v, const J2Plasticity& law) {
  Single out;
  std::vector<int> ids;
  int id = 1;
  for (const Eigen::Vector2d& xi : plane_shape_nodes_xi(v.shape)) {
    ids.push_back(id++);
    out.x.push_back(distort(0.8 * xi(0), 0.9 * xi(1)));
  }
  PlaneSolidOptions o{v.shape, v.behaviour, v.technology, 0.7};
  out.element =
      std::make_unique<PlaneSolid>(1, ids, out.x, IsotropicElasticity{kE, kNu, 0.0}, o,
                                   std::vector<std::vector<int>>{}, SourceLocation{}, law);
  return out;
}

/// A homogeneous in-plane gradient H (scaled); in axisymmetry without shear (u_r = H00 r keeps
/// the hoop strain u_r / r = H00 uniform; a shear u_r ∝ z would not).
Eigen::Matrix2d gradient(const Variant& v, double scale) {
  Eigen::Matrix2d h;
  h << 0.004, 0.0012, -0.0007, -0.0015;
  if (v.behaviour == PlaneBehaviour::Axisymmetric) h(0, 1) = h(1, 0) = 0.0;
  return scale * h;
}

Eigen::VectorXd nodal(const std::vector<Vec3>& x, const Eigen::Matrix2d& h) {
  Eigen::VectorXd u(2 * static_cast<int>(x.size()));
  for (std::size_t a = 0; a < x.size(); ++a) u.segment<2>(2 * a) = h * x[a].head<2>();
  return u;
}

/// The material point of the homogeneous strain: its state after the return.
PlasticState point_return(const Variant& v, const J2Plasticity& law, const PlasticState& c,
                          const Eigen::Matrix2d& h) {
  PlasticState next;
  if (v.behaviour == PlaneBehaviour::PlaneStress) {
    Vector5d e;
    e << h(0, 0), h(1, 1), h(0, 1) + h(1, 0), 0.0, 0.0;
    law.plane_stress(c, e, &next);
  } else {
    Vector6d e = Vector6d::Zero();
    e << h(0, 0), h(1, 1), v.behaviour == PlaneBehaviour::Axisymmetric ? h(0, 0) : 0.0,
        h(0, 1) + h(1, 0), 0.0, 0.0;
    law.solid(c, e, &next);
  }
  return next;
}

TEST(PlasticPlanes, HomogeneousStrainGivesTheMaterialPointAtEveryStiffnessPoint) {
  for (bool kinematic : {false, true}) {
    const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, kinematic);
    for (const Variant& v : variants()) {
      Single s = single(v, law);
      PlasticState point;
      double volume = 0.0;
      for (double scale : {1.0, 2.0, 1.7, -1.0}) {  // loading, elastic unloading, reversal
        const Eigen::Matrix2d h = gradient(v, scale);
        s.element->commit_history({}, nodal(s.x, h));
        point = point_return(v, law, point, h);
        for (int p = 0; p < s.element->n_points(); ++p) {
          const PlasticState& st = s.element->point_state(p);
          EXPECT_LT((st.plastic_strain - point.plastic_strain).norm(),
                    1e-9 * point.plastic_strain.norm())
              << name(v) << " point " << p << " scale " << scale;
          EXPECT_LT((st.stress - point.stress).norm(), 1e-8 * kSy) << name(v);
          EXPECT_NEAR(st.alpha, point.alpha, 1e-12) << name(v);
        }
      }
      ASSERT_GT(point.alpha, 0.0) << name(v);
      // The element's plastic work is the point's work per volume times the volume of the
      // stiffness rule (the volume() of the mass rule differs from it where neither is exact:
      // the curved 8-node and 6-node shapes, 1e-3 here).
      volume = s.element->plastic_work() / point.plastic_work;
      EXPECT_NEAR(volume, *s.element->volume(), 1e-3 * volume) << name(v);
      // The results at u: the point's stress and plastic strain (volume averages).
      ElementResultValues r;
      s.element->results({}, nodal(s.x, gradient(v, -1.0)), {}, r);
      EXPECT_NEAR(r[0], point.stress(0), 1e-8 * kSy) << name(v);
      EXPECT_NEAR(r[9], point.plastic_strain(0), 1e-9 * point.alpha) << name(v);
      EXPECT_NEAR(r[13], point.alpha, 1e-9 * point.alpha) << name(v);
    }
  }
}

TEST(PlasticPlanes, ElementTangentMatchesFiniteDifferences) {
  for (bool kinematic : {false, true}) {
    const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, kinematic);
    for (const Variant& v : variants()) {
      Single s = single(v, law);
      s.element->commit_history({}, nodal(s.x, gradient(v, 1.0)));
      // A non-homogeneous state beyond the committed one (bending-like on top).
      Eigen::VectorXd u = nodal(s.x, gradient(v, 1.6));
      for (std::size_t a = 0; a < s.x.size(); ++a)
        u(2 * static_cast<int>(a)) += 0.002 * (s.x[a].y() - 0.5) * (s.x[a].y() - 0.5);
      Eigen::MatrixXd k, kp, km;
      Eigen::VectorXd f, fp, fm;
      s.element->tangent({}, u, k, f);
      const int n = static_cast<int>(u.size());
      Eigen::MatrixXd fd(n, n);
      const double step = 1e-8;
      for (int j = 0; j < n; ++j) {
        Eigen::VectorXd up = u, um = u;
        up(j) += step;
        um(j) -= step;
        s.element->tangent({}, up, kp, fp);
        s.element->tangent({}, um, km, fm);
        fd.col(j) = (fp - fm) / (2.0 * step);
      }
      EXPECT_LT((k - fd).norm(), 1e-5 * k.norm()) << name(v);
      // Not the elastic stiffness: the state is plastic.
      EXPECT_GT((k - s.element->stiffness()).norm(), 1e-3 * k.norm()) << name(v);
      // Translation along Y (rigid also in axisymmetry): no force.
      Eigen::VectorXd shift = Eigen::VectorXd::Zero(n);
      for (int a = 0; a < n / 2; ++a) shift(2 * a + 1) = 0.3;
      s.element->tangent({}, u + shift, kp, fp);
      EXPECT_LT((fp - f).norm(), 1e-9 * f.norm()) << name(v);
    }
  }
}

/// A displacement with a strain gradient (u = s (H x + quadratic terms)): the stiffness points of
/// one element see different strains, so that only some of them yield at a moderate scale.
Eigen::VectorXd graded(const Variant& v, const std::vector<Vec3>& x, double scale) {
  const Eigen::Matrix2d h = gradient(v, 1.0);
  Eigen::VectorXd u(2 * static_cast<int>(x.size()));
  for (std::size_t a = 0; a < x.size(); ++a) {
    const double dx = x[a](0) - 2.0, dy = x[a](1) - 0.5;
    const Eigen::Vector2d quadratic(0.004 * dx * dx, v.behaviour == PlaneBehaviour::Axisymmetric
                                                         ? 0.003 * dy * dy
                                                         : 0.003 * dx * dx);
    u.segment<2>(2 * a) = scale * (h * x[a].head<2>() + quadratic);
  }
  return u;
}

TEST(PlasticPlanes, ElementNodalStressesFollowTheEresxDefault) {
  // MAPDL's ERESX default: integration-point stresses extrapolated to the nodes while the
  // element is elastic (the values of nodal_results()), copied from the nearest point once a
  // point carries plastic strain (a node equally near two points, a midside node, takes their
  // mean). Those nodal values are what ESOL,,ELEM,NODE reads (vmr049-pl5: the bore node).
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, false);
  for (const Variant& v : variants()) {
    SCOPED_TRACE(name(v));
    // Elastic: a small load; the nodal values equal the extrapolation of nodal_results().
    {
      Single s = single(v, law);
      const Eigen::VectorXd u = graded(v, s.x, 0.05);
      s.element->commit_history({}, u);
      for (int p = 0; p < s.element->n_points(); ++p)
        ASSERT_EQ(s.element->point_state(p).alpha, 0.0);
      std::vector<int> ids;
      for (std::size_t a = 0; a < s.x.size(); ++a) ids.push_back(static_cast<int>(a) + 1);
      const PlaneSolid elastic(1, ids, s.x, IsotropicElasticity{kE, kNu, 0.0},
                               PlaneSolidOptions{v.shape, v.behaviour, v.technology, 0.7},
                               std::vector<std::vector<int>>{});
      std::map<int, ElementResultValues> extrapolated;
      ASSERT_TRUE(elastic.nodal_results({}, u, extrapolated));
      const std::vector<Eigen::Vector4d> at_nodes = s.element->element_nodal_stresses({}, u);
      for (std::size_t a = 0; a < ids.size(); ++a)
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(at_nodes[a](c), extrapolated.at(ids[a])[static_cast<std::size_t>(c)],
                      1e-9 * kSy);
    }
    Single s = single(v, law);
    const Eigen::VectorXd u = graded(v, s.x, 1.0);
    s.element->commit_history({}, u);
    bool yielded = false;
    for (int p = 0; p < s.element->n_points(); ++p)
      yielded = yielded || s.element->point_state(p).alpha > 0.0;
    ASSERT_TRUE(yielded);
    const std::vector<Eigen::Vector4d> at_nodes = s.element->element_nodal_stresses({}, u);
    const auto xi_nodes = plane_shape_nodes_xi(v.shape);
    ASSERT_EQ(at_nodes.size(), xi_nodes.size());
    for (std::size_t k = 0; k < xi_nodes.size(); ++k) {
      double nearest = 1e300;
      for (int p = 0; p < s.element->n_points(); ++p)
        nearest = std::min(nearest, (s.element->point_xi(p) - xi_nodes[k]).norm());
      Eigen::Vector4d expected = Eigen::Vector4d::Zero();
      int count = 0;
      for (int p = 0; p < s.element->n_points(); ++p)
        if ((s.element->point_xi(p) - xi_nodes[k]).norm() < nearest + 1e-9) {
          expected += s.element->point_state(p).stress.head<4>();
          ++count;
        }
      expected /= count;
      EXPECT_LE((at_nodes[k] - expected).norm(), 1e-9 * kSy) << "node " << k;
    }
  }
}

TEST(PlasticPlanes, RestartStateRoundTrip) {
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, true);
  for (const Variant& v : variants()) {
    Single a = single(v, law), b = single(v, law);
    a.element->commit_history({}, nodal(a.x, gradient(v, 2.0)));
    const std::vector<double> saved = a.element->history_state();
    ASSERT_FALSE(saved.empty());
    b.element->restore_history_state(saved);
    EXPECT_EQ(b.element->history_state(), saved) << name(v);
    EXPECT_EQ(b.element->plastic_work(), a.element->plastic_work());
    const Eigen::VectorXd u = nodal(a.x, gradient(v, -0.5));
    Eigen::MatrixXd ka, kb;
    Eigen::VectorXd fa, fb;
    a.element->tangent({}, u, ka, fa);
    b.element->tangent({}, u, kb, fb);
    EXPECT_EQ(fa, fb) << name(v);
    EXPECT_EQ(ka, kb) << name(v);
    EXPECT_ANY_THROW(b.element->restore_history_state({1.0, 2.0}));
  }
}

/// One unit-square element (PLANE182, or PLANE183 with midside nodes) stretched along `axis`
/// (0 X, 1 Y) with the other direction free, one load step per strain.
std::string stretch_deck(const char* type, int keyopt3, int axis, double tangent,
                         const std::vector<double>& strains, int substeps = 1) {
  std::ostringstream d;
  d << "/PREP7\nET,1," << type << ",,," << keyopt3 << "\nMP,EX,1," << kE << "\nMP,PRXY,1," << kNu
    << "\nTB,BISO,1\nTBDATA,1," << kSy << "," << tangent << "\n";
  // Axisymmetric: the square at 1 <= r <= 2 (radial stretch would not be uniaxial; axial is).
  const double x0 = keyopt3 == 1 ? 1.0 : 0.0;
  d << "N,1," << x0 << ",0\nN,2," << x0 + 1 << ",0\nN,3," << x0 + 1 << ",1\nN,4," << x0 << ",1\n";
  const bool quadratic = std::string(type) == "PLANE183";
  if (quadratic)
    d << "N,5," << x0 + 0.5 << ",0\nN,6," << x0 + 1 << ",0.5\nN,7," << x0 + 0.5 << ",1\nN,8," << x0
      << ",0.5\nE,1,2,3,4,5,6,7,8\n";
  else
    d << "E,1,2,3,4\n";
  d << "FINISH\n/SOLU\nANTYPE,STATIC\nCNVTOL,F,,1E-8\n";
  // Fixed edge, the opposite edge moved; one node holds the free direction.
  const char* along = axis == 0 ? "UX" : "UY";
  const std::vector<int> fixed = axis == 0 ? std::vector<int>{1, 4} : std::vector<int>{1, 2};
  const std::vector<int> moved = axis == 0 ? std::vector<int>{2, 3} : std::vector<int>{3, 4};
  for (int n : fixed) d << "D," << n << "," << along << ",0\n";
  if (quadratic) d << "D," << (axis == 0 ? 8 : 5) << "," << along << ",0\n";
  if (keyopt3 != 1) d << "D,1," << (axis == 0 ? "UY" : "UX") << ",0\n";
  for (std::size_t s = 0; s < strains.size(); ++s) {
    d << "TIME," << s + 1 << "\nNSUBST," << substeps << "\n";
    for (int n : moved) d << "D," << n << "," << along << "," << strains[s] << "\n";
    if (quadratic) {
      // The midside nodes of the two free edges at half the stretch: every displacement along
      // the stretch is prescribed (with Et = 0 a free one would leave a mechanism of
      // isochoric flow along the yield normal in the 8-node element).
      d << "D," << (axis == 0 ? 6 : 7) << "," << along << "," << strains[s] << "\n";
      for (int n : axis == 0 ? std::vector<int>{5, 7} : std::vector<int>{6, 8})
        d << "D," << n << "," << along << "," << 0.5 * strains[s] << "\n";
    }
    d << "SOLVE\n";
  }
  d << "FINISH\n";
  return d.str();
}

TEST(PlasticPlanes, UniaxialStretchMatchesTheBilinearClosedForm) {
  // σ = σy + Et (ε − σy/E) beyond yield, elastic unloading by E Δε: plane stress stretched along
  // X, and the axisymmetric ring stretched along its axis Y (σr = σθ = 0).
  const double ey = kSy / kE;
  const std::vector<double> strains = {0.5 * ey, 3.0 * ey, 2.5 * ey};
  const double s2 = kSy + kEt * (3.0 * ey - ey);
  const std::vector<double> expected = {0.5 * kSy, s2, s2 - kE * 0.5 * ey};
  const std::vector<double> eppl = {0.0, 3.0 * ey - s2 / kE, 3.0 * ey - s2 / kE};
  for (const char* type : {"PLANE182", "PLANE183"})
    for (int keyopt3 : {0, 1}) {
      const int axis = keyopt3 == 1 ? 1 : 0;
      const auto run = testing::run_deck_text(fmt::format("plane_stretch_{}_{}", type, keyopt3),
                                              stretch_deck(type, keyopt3, axis, kEt, strains));
      const char* s_item = axis == 0 ? "SX" : "SY";
      const char* e_item = axis == 0 ? "EPPLX" : "EPPLY";
      for (std::size_t s = 0; s < strains.size(); ++s) {
        const double t = s + 1.0;
        EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(1, s_item), t), expected[s],
                    1e-8 * kSy)
            << type << " KEYOPT(3) " << keyopt3 << " step " << s + 1;
        EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(1, e_item), t), eppl[s],
                    1e-10)
            << type << " KEYOPT(3) " << keyopt3;
        const char* other = axis == 0 ? "SY" : "SX";
        EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(1, other), t), 0.0,
                    1e-8 * kSy);
      }
    }
}

TEST(PlasticPlanes, PlaneStrainStretchApproachesTwoOverRootThreeYield) {
  // Elastic-perfectly plastic plane strain, σy free: as the plastic flow takes over (plastic
  // Poisson ratio 1/2) σz → σx/2 and von Mises gives σx → 2σy/√3 (the plane-strain yield
  // stress, Hill 1950). The approach is exponential in the plastic strain along the path: 40
  // substeps of εy each to ε = 42 εy leave σx within 1e-6 of the limit and σz/σx within
  // 1e-6 of 1/2 (measured 4e-15 for both).
  const double ey = kSy / kE;
  for (const char* type : {"PLANE182", "PLANE183"}) {
    const auto run = testing::run_deck_text(fmt::format("plane_strain_limit_{}", type),
                                            stretch_deck(type, 2, 0, 0.0, {2 * ey, 42 * ey}, 40));
    const double sx = testing::value_stored_at(run.reader->element_series(1, "SX"), 2.0);
    const double sz = testing::value_stored_at(run.reader->element_series(1, "SZ"), 2.0);
    EXPECT_NEAR(sx, 2.0 / std::sqrt(3.0) * kSy, 1e-6 * kSy) << type;
    EXPECT_NEAR(sz / sx, 0.5, 1e-6) << type;
    EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(1, "SEQV"), 2.0), kSy,
                1e-6 * kSy);
  }
}

TEST(PlasticPlanes, DistortedPatchReproducesTheHomogeneousPlasticState) {
  // 2x2 elements on the unit square (X + 1 in axisymmetry) with the centre node moved off
  // centre (midside nodes of the inner edges at their midpoints); every boundary node follows
  // u = H x, the inner nodes are free. Steps H, 2H, −H (plastic loading, further loading,
  // reversal): the inner nodes land on u = H x and every element carries the plastic strain of
  // the material point (BKIN).
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, true);
  struct Case {
    const char* type;
    int keyopt1, keyopt3;
  };
  const std::vector<Case> cases = {{"PLANE182", 0, 0}, {"PLANE182", 0, 1}, {"PLANE182", 0, 2},
                                   {"PLANE182", 3, 0}, {"PLANE182", 3, 1}, {"PLANE182", 3, 2},
                                   {"PLANE182", 1, 0}, {"PLANE182", 1, 1}, {"PLANE182", 1, 2},
                                   {"PLANE183", 0, 0}, {"PLANE183", 0, 1}, {"PLANE183", 0, 2}};
  for (const Case& c : cases) {
    const bool quadratic = std::string(c.type) == "PLANE183";
    const Variant v{PlaneShape::Quad4, PlaneTechnology::Standard,
                    c.keyopt3 == 0   ? PlaneBehaviour::PlaneStress
                    : c.keyopt3 == 1 ? PlaneBehaviour::Axisymmetric
                                     : PlaneBehaviour::PlaneStrain};
    std::ostringstream deck;
    deck << "/PREP7\nET,1," << c.type << "," << c.keyopt1 << ",," << c.keyopt3 << "\nMP,EX,1," << kE
         << "\nMP,PRXY,1," << kNu << "\nTB,BKIN,1\nTBDATA,1," << kSy << "," << kEt << "\n";
    auto id = [](int i, int j) { return 1 + i + 5 * j; };  // on the 5x5 grid of quarter points
    const double x0 = c.keyopt3 == 1 ? 1.0 : 0.0;
    const Vec3 centre(x0 + 0.5 + 0.08, 0.5 - 0.06, 0.0);
    std::map<int, Vec3> x;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) {
        if (i % 2 == 1 && j % 2 == 1) continue;                  // no node there
        if (!quadratic && (i % 2 == 1 || j % 2 == 1)) continue;  // corners only
        Vec3 p(x0 + 0.25 * i, 0.25 * j, 0.0);
        if (i == 2 && j == 2) p = centre;
        // Inner-edge midsides: halfway between their corners (straight edges).
        if (i == 2 && (j == 1 || j == 3)) p = 0.5 * (centre + Vec3(x0 + 0.5, j == 1 ? 0 : 1, 0));
        if (j == 2 && (i == 1 || i == 3)) p = 0.5 * (centre + Vec3(x0 + (i == 1 ? 0 : 1), 0.5, 0));
        x[id(i, j)] = p;
        deck << fmt::format("N,{},{:.15g},{:.15g}\n", id(i, j), p.x(), p.y());
      }
    for (int ej = 0; ej < 2; ++ej)
      for (int ei = 0; ei < 2; ++ei) {
        const int i = 2 * ei, j = 2 * ej;
        deck << "E," << id(i, j) << "," << id(i + 2, j) << "," << id(i + 2, j + 2) << ","
             << id(i, j + 2);
        if (quadratic)
          deck << "," << id(i + 1, j) << "," << id(i + 2, j + 1) << "," << id(i + 1, j + 2) << ","
               << id(i, j + 1);
        deck << "\n";
      }
    deck << "FINISH\n/SOLU\nANTYPE,STATIC\nCNVTOL,F,,1E-8\n";
    const std::vector<double> scales = {1.0, 2.0, -1.0};
    auto boundary = [&](int node) {
      const int i = (node - 1) % 5, j = (node - 1) / 5;
      return i == 0 || i == 4 || j == 0 || j == 4;
    };
    for (std::size_t s = 0; s < scales.size(); ++s) {
      const Eigen::Matrix2d h = gradient(v, scales[s]);
      deck << "TIME," << s + 1 << "\n";
      for (const auto& [node, p] : x) {
        if (!boundary(node)) continue;
        const Eigen::Vector2d u = h * p.head<2>();
        deck << fmt::format("D,{},UX,{:.17g}\nD,{},UY,{:.17g}\n", node, u.x(), node, u.y());
      }
      deck << "SOLVE\n";
    }
    deck << "FINISH\n";
    const std::string tag = fmt::format("plane_patch_{}_{}_{}", c.type, c.keyopt1, c.keyopt3);
    const auto run = testing::run_deck_text(tag, deck.str());
    PlasticState point;
    for (std::size_t s = 0; s < scales.size(); ++s) {
      const Eigen::Matrix2d h = gradient(v, scales[s]);
      point = point_return(v, law, point, h);
      ASSERT_GT(point.alpha, 0.0);
      const double t = s + 1.0;
      for (const auto& [node, p] : x) {
        if (boundary(node)) continue;
        const Eigen::Vector2d u = h * p.head<2>();
        EXPECT_NEAR(testing::value_stored_at(run.reader->nodal_series(node, "UX"), t), u.x(), 1e-9)
            << tag << " node " << node;
        EXPECT_NEAR(testing::value_stored_at(run.reader->nodal_series(node, "UY"), t), u.y(), 1e-9)
            << tag << " node " << node;
      }
      const char* items[4] = {"EPPLX", "EPPLY", "EPPLZ", "EPPLXY"};
      for (int e = 1; e <= 4; ++e)
        for (int k = 0; k < 4; ++k)
          EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(e, items[k]), t),
                      point.plastic_strain(k), 1e-8 * point.plastic_strain.norm())
              << tag << " element " << e << " " << items[k] << " step " << s + 1;
    }
  }
}

TEST(PlasticPlanes, CreepThroughTheElementAtConstantLoadMatchesTimeHardening) {
  // J2Plasticity::creep (modified time hardening, TBOPT 6) in a plane-stress PLANE182 square
  // under a constant axial force, Y free: uniaxial σ = F/A at every point, and the creep strain
  // ε_cr(t) = C1 σ^C2 t^(C3+1)/(C3+1) (the law's strain, differenced over each step: exact at
  // constant stress, any step). The global Newton iteration on the element tangent finds the
  // strain of each step.
  const double c1 = 2e-12, c2 = 3.0, c3 = -0.5, sigma = 120.0, thickness = 0.7;
  auto clock = std::make_shared<CreepClock>();
  clock->active = true;
  const auto law = J2Plasticity::creep(kE, kNu, CreepLaw{6, {c1, c2, c3, 0.0}}, clock);
  for (PlaneShape shape : {PlaneShape::Quad4, PlaneShape::Quad8}) {
    std::vector<Vec3> x;
    std::vector<int> ids;
    for (const Eigen::Vector2d& xi : plane_shape_nodes_xi(shape)) {
      x.push_back(Vec3(0.5 * (xi(0) + 1), 0.5 * (xi(1) + 1), 0.0));
      ids.push_back(static_cast<int>(ids.size()) + 1);
    }
    PlaneSolidOptions o{shape, PlaneBehaviour::PlaneStress, PlaneTechnology::Standard, thickness};
    PlaneSolid el(1, ids, x, IsotropicElasticity{kE, kNu, 0.0}, o, {}, {}, law);
    const int n = 2 * static_cast<int>(x.size());
    // Consistent nodal forces of the traction σ on the edge X = 1 (thickness t, length 1).
    Eigen::VectorXd load = Eigen::VectorXd::Zero(n);
    std::vector<bool> fixed(static_cast<std::size_t>(n), false);
    for (std::size_t a = 0; a < x.size(); ++a) {
      const bool corner = a < 4;
      if (x[a].x() == 1.0)
        load(2 * a) = sigma * thickness *
                      (shape == PlaneShape::Quad4 ? 0.5
                       : corner                   ? 1.0 / 6.0
                                                  : 2.0 / 3.0);
      if (x[a].x() == 0.0) fixed[2 * a] = true;
      if (x[a].x() == 0.0 && x[a].y() == 0.0) fixed[2 * a + 1] = true;
    }
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    const double t_end = 400.0;
    const int steps = 5;
    for (int i = 1; i <= steps; ++i) {
      clock->time = t_end * i / steps;
      clock->dt = t_end / steps;
      for (int it = 0; it < 30; ++it) {
        Eigen::MatrixXd k;
        Eigen::VectorXd f;
        el.tangent({}, u, k, f);
        Eigen::VectorXd r = load - f;
        for (int d = 0; d < n; ++d)
          if (fixed[static_cast<std::size_t>(d)]) {
            r(d) = 0.0;
            k.row(d).setZero();
            k.col(d).setZero();
            k(d, d) = 1.0;
          }
        if (r.norm() <= 1e-11 * load.norm()) break;
        u += k.ldlt().solve(r);
      }
      el.commit_history({}, u);
    }
    const double creep = c1 * std::pow(sigma, c2) * std::pow(t_end, c3 + 1.0) / (c3 + 1.0);
    for (int p = 0; p < el.n_points(); ++p) {
      const PlasticState& st = el.point_state(p);
      EXPECT_NEAR(st.stress(0), sigma, 1e-8 * sigma) << "shape " << static_cast<int>(shape);
      EXPECT_NEAR(st.plastic_strain(0), creep, 1e-8 * creep);
      EXPECT_NEAR(st.plastic_strain(1), -0.5 * creep, 1e-8 * creep);  // isochoric flow
    }
    // Results: the creep strain as EPCR (X, Y, Z, EQV = ε_cr in uniaxial stress, CREQ), the
    // plastic items 0; SX the applied stress.
    ElementResultValues r;
    el.results({}, u, {}, r);
    ASSERT_EQ(r.size(), plane_solid_result_names().size());
    EXPECT_NEAR(r[0], sigma, 1e-8 * sigma);
    EXPECT_EQ(r[9], 0.0);                            // EPPLX
    EXPECT_EQ(r[13], 0.0);                           // EPEQ
    EXPECT_NEAR(r[17], creep, 1e-8 * creep);         // EPCRX
    EXPECT_NEAR(r[18], -0.5 * creep, 1e-8 * creep);  // EPCRY
    EXPECT_NEAR(r[19], -0.5 * creep, 1e-8 * creep);  // EPCRZ
    EXPECT_NEAR(r[21], creep, 1e-8 * creep);         // EPCR EQV
    EXPECT_NEAR(r[22], creep, 1e-8 * creep);         // CREQ
    // The end's stretch: elastic plus creep strain.
    for (std::size_t a = 0; a < x.size(); ++a)
      if (x[a].x() == 1.0) EXPECT_NEAR(u(2 * a), sigma / kE + creep, 1e-9 * (sigma / kE));
  }
}

}  // namespace
}  // namespace impactfe::test_plastic_planes
