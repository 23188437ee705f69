// The element status loop with its chatter guard (src/nonlinear/status_loop.h): a COMBIN40 gap
// that closes is detected once and committed; an element that keeps flipping is frozen at the
// chatter limit, named in the report, and released at the end of the step.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "assembly/assembler.h"
#include "assembly/dof_map.h"
#include "elements/element.h"
#include "nonlinear/status_loop.h"

namespace impactfe::test_status_loop {
namespace {

/// A one-DOF element whose status flips at every update unless frozen (a contact that never
/// settles).
class FlippingContact final : public Element {
 public:
  explicit FlippingContact(int id, int node) : Element(id), dofs_{{node, Dof::UX}} {}
  const char* family() const override { return "FlippingContact"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return true; }
  void tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f) const override {
    K = Eigen::MatrixXd::Constant(1, 1, closed_ ? 1.0 : 0.0);
    f = K * u;
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override { M.setZero(1, 1); }
  bool has_status() const override { return true; }
  bool update_status(const ElementContext&, const Eigen::VectorXd&) override {
    if (frozen_) return false;
    closed_ = !closed_;
    return true;
  }
  void freeze_status(bool frozen) override { frozen_ = frozen; }
  bool frozen() const { return frozen_; }
  const std::vector<std::string>& result_names() const override { return names_; }
  void results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out.clear();
  }

 private:
  std::vector<DofKey> dofs_;
  std::vector<std::string> names_;
  bool closed_ = false, frozen_ = false;
};

/// Node 1 (ground) - COMBIN40 gap (K1 = 1000, GAP = 0.1) - node 2, along UX.
std::unique_ptr<Element> gap_element() {
  Model m;
  m.nodes[1] = Node{1, Vec3(0, 0, 0)};
  m.nodes[2] = Node{2, Vec3(1, 0, 0)};
  ElementType et;
  et.id = 1;
  et.ansys_name = "COMBIN40";
  m.element_types[1] = et;
  m.real_sets[1] = RealSet{1, {1000.0, 0.0, 0.0, 0.1, 0.0, 0.0}};
  ElementRecord r;
  r.id = 7;
  r.nodes = {1, 2};
  return create_element(ElementBuildContext{m, {}}, r);
}

TEST(StatusLoop, AGapThatClosesIsDetectedOnceAndCommitted) {
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(gap_element());
  const DofMap dofs(elements, {});
  const Assembler assembler(elements, dofs, ElementContext{});
  StatusLoop loop(elements, assembler);
  ASSERT_FALSE(loop.empty());
  EXPECT_EQ(elements[0]->status(), GapStatus::Open);

  VectorXd u = VectorXd::Zero(dofs.n_active());
  u(dofs.index({2, Dof::UX})) = -0.15;  // node 2 moved 0.15 toward node 1: gap 0.1 closed
  loop.begin_step();
  EXPECT_EQ(loop.update(u, StepLabel{1, 1, 0.1}), 1);
  EXPECT_EQ(elements[0]->status(), GapStatus::Closed);
  EXPECT_EQ(loop.update(u, StepLabel{1, 1, 0.1}), 0);  // settled
  loop.end_step();
  loop.commit(u);
  EXPECT_EQ(loop.n_changes(), 1);
  EXPECT_EQ(loop.chatter_report(), "");

  // Reopening in the next step is one more change.
  u.setZero();
  loop.begin_step();
  EXPECT_EQ(loop.update(u, StepLabel{1, 2, 0.2}), 1);
  EXPECT_EQ(elements[0]->status(), GapStatus::Open);
}

TEST(StatusLoop, AChatteringElementIsFrozenAndReported) {
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(std::make_unique<FlippingContact>(42, 1));
  auto* contact = static_cast<FlippingContact*>(elements[0].get());
  const DofMap dofs(elements, {});
  const Assembler assembler(elements, dofs, ElementContext{});
  StatusLoop loop(elements, assembler, /*chatter_limit=*/4);
  const VectorXd u = VectorXd::Zero(dofs.n_active());

  loop.begin_step();
  int changes = 0;
  for (int iteration = 0; iteration < 10; ++iteration) changes += loop.update(u, {3, 7, 0.5});
  EXPECT_EQ(changes, 4);  // frozen at the fourth change, quiet afterwards
  EXPECT_TRUE(contact->frozen());
  EXPECT_EQ(loop.chatter_report(), " 42(4x)");
  loop.end_step();
  EXPECT_FALSE(contact->frozen());  // the next step starts free

  loop.begin_step();
  EXPECT_EQ(loop.chatter_report(), "");
  EXPECT_EQ(loop.update(u, {3, 8, 0.6}), 1);
}

}  // namespace
}  // namespace impactfe::test_status_loop
