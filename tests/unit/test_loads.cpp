// Loads of a load step (spec §3.20): KBC ramped loads go linearly from the previous step's value,
// stepped loads apply in full; a load removed in the next step is step-removed; forces on
// constrained DOFs are dropped (the constraint wins); prescribed displacements ramp the same way.
#include <gtest/gtest.h>

#include "assembly/loads.h"

namespace impactfe::test_loads {
namespace {

class LoadsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Model m;
    m.nodes[1] = Node{1, Vec3::Zero(), Vec3::Zero()};
    m.nodes[2] = Node{2, Vec3(1, 0, 0), Vec3::Zero()};
    ElementType t;
    t.id = 1;
    t.ansys_name = "LINK8";
    m.element_types[1] = t;
    m.real_sets[1] = RealSet{1, {1.0}};
    Material mat;
    mat.id = 1;
    mat.props = {{"EX", 1.0}};
    m.materials[1] = mat;
    ElementRecord r;
    r.id = 1;
    r.nodes = {1, 2};
    m.elements[1] = r;
    model_ = m;
    elements_.push_back(create_element(ElementBuildContext{model_, {}}, model_.elements.at(1)));
    dofs_ = std::make_unique<DofMap>(elements_, std::set<DofKey>{{1, Dof::UX}});
  }
  double force(const VectorXd& f, int node, Dof dof) const { return f(dofs_->index({node, dof})); }

  Model model_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::unique_ptr<DofMap> dofs_;
};

TEST_F(LoadsTest, RampedLoadsStartFromThePreviousStep) {
  LoadStep first, second;
  first.forces[{2, Dof::UX}] = 10.0;
  second.forces[{2, Dof::UX}] = 30.0;
  second.forces[{2, Dof::UY}] = 8.0;  // new in step 2: ramps from zero
  second.stepped = false;
  const VectorXd f = nodal_forces(*dofs_, LoadPoint{&second, &first, 0.25});
  EXPECT_DOUBLE_EQ(force(f, 2, Dof::UX), 15.0);
  EXPECT_DOUBLE_EQ(force(f, 2, Dof::UY), 2.0);
}

TEST_F(LoadsTest, SteppedLoadsApplyInFullAndRemovedLoadsVanish) {
  LoadStep first, second;
  first.forces[{2, Dof::UX}] = 10.0;
  first.forces[{2, Dof::UZ}] = 5.0;
  second.forces[{2, Dof::UX}] = 30.0;  // UZ removed
  second.stepped = true;
  const VectorXd f = nodal_forces(*dofs_, LoadPoint{&second, &first, 0.25});
  EXPECT_DOUBLE_EQ(force(f, 2, Dof::UX), 30.0);
  EXPECT_DOUBLE_EQ(force(f, 2, Dof::UZ), 0.0);
  second.stepped = false;  // removed loads are step-removed when ramped too
  const VectorXd g = nodal_forces(*dofs_, LoadPoint{&second, &first, 0.25});
  EXPECT_DOUBLE_EQ(force(g, 2, Dof::UZ), 0.0);
}

TEST_F(LoadsTest, ConstraintWinsOverAForceAndPrescribedValuesRamp) {
  LoadStep step;
  step.forces[{1, Dof::UX}] = 99.0;  // node 1 UX is constrained
  step.constraints[{1, Dof::UX}] = 0.2;
  const VectorXd f = nodal_forces(*dofs_, LoadPoint{&step, nullptr, 1.0});
  EXPECT_EQ(f.norm(), 0.0);
  const VectorXd u = prescribed_displacements(*dofs_, LoadPoint{&step, nullptr, 0.5});
  EXPECT_DOUBLE_EQ(u(dofs_->index({1, Dof::UX})), 0.1);
}

TEST_F(LoadsTest, FrameAccelerationRamps) {
  LoadStep first, second;
  first.acel = Vec3(0, 0, 0);
  second.acel = Vec3(0, 0, 386.4);
  EXPECT_DOUBLE_EQ(frame_acceleration(LoadPoint{&second, &first, 0.5}).z(), 193.2);
  second.stepped = true;
  EXPECT_DOUBLE_EQ(frame_acceleration(LoadPoint{&second, &first, 0.5}).z(), 386.4);
}

}  // namespace
}  // namespace impactfe::test_loads
