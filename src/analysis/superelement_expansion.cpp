#include "analysis/superelement_expansion.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <set>

#include "core/errors.h"

namespace impactfe {

SuperelementExpansion::SuperelementExpansion(SuperelementData data) : data_(std::move(data)) {
  bool lumped = false, sstif = false;
  model_ = std::make_unique<Model>(deserialize_generation_model(data_.model_text, lumped, sstif));
  model_->title = data_.title;
  model_->jobname = data_.name;
  AnalysisOptions options;
  options.type = AnalysisType::Substructure;
  options.lumped_mass = lumped;
  options.stress_stiffening = sstif;
  structure_ = std::make_unique<Structure>(*model_, options, RunSettings{});
  const std::set<DofKey> constrained(data_.constrained.begin(), data_.constrained.end());
  dofs_ = std::make_unique<DofMap>(structure_->elements(), constrained);
  assembler_ = std::make_unique<Assembler>(structure_->elements(), *dofs_, structure_->context());
  if (dofs_->n_free() != data_.n_masters() + data_.n_slaves())
    throw InputError(fmt::format(
        "superelement {}: the rebuilt model has {} free DOFs, the file {} masters + {} slaves",
        data_.name, dofs_->n_free(), data_.n_masters(), data_.n_slaves()));
  auto index_of = [this](const DofKey& key) {
    const int i = dofs_->index(key);
    if (i < 0 || i >= dofs_->n_free())
      throw InputError(fmt::format("superelement {}: {} is not a free DOF of the rebuilt model",
                                   data_.name, describe(key)));
    return i;
  };
  for (const auto& m : data_.masters) master_index_.push_back(index_of(m.key));
  for (const auto& s : data_.slaves) slave_index_.push_back(index_of(s));
}

SuperelementExpansion::~SuperelementExpansion() = default;

VectorXd SuperelementExpansion::expand_motion(const VectorXd& xm) const {
  VectorXd x = VectorXd::Zero(dofs_->n_active());
  const VectorXd xs = data_.transformation * xm;
  for (std::size_t k = 0; k < master_index_.size(); ++k) x(master_index_[k]) = xm(int(k));
  for (std::size_t k = 0; k < slave_index_.size(); ++k) x(slave_index_[k]) = xs(int(k));
  return x;
}

VectorXd SuperelementExpansion::expand_displacement(const VectorXd& um, const Vec3& acel,
                                                    const std::vector<double>& load_scales) const {
  VectorXd u = expand_motion(um);
  VectorXd correction = -(data_.acceleration_correction * acel);
  for (std::size_t i = 0; i < load_scales.size(); ++i) {
    if (int(i) >= data_.load_correction.cols())
      throw InputError(fmt::format("superelement {} has {} load vectors, not {}", data_.name,
                                   data_.load_correction.cols(), load_scales.size()));
    correction += load_scales[i] * data_.load_correction.col(int(i));
  }
  for (std::size_t k = 0; k < slave_index_.size(); ++k) u(slave_index_[k]) += correction(int(k));
  return u;
}

TimePoint SuperelementExpansion::time_point(double time, const VectorXd& um, const VectorXd& vm,
                                            const VectorXd& am, const Vec3& acel) const {
  TimePoint p;
  p.time = time;
  const VectorXd u = expand_displacement(um, acel);
  const VectorXd v = expand_motion(vm);
  const VectorXd a = expand_motion(am);
  p.displacement = structure_->nodal_table(*dofs_, u);
  p.velocity = structure_->nodal_table(*dofs_, v);
  p.acceleration = structure_->nodal_table(*dofs_, a);
  p.reaction =
      Eigen::MatrixXd::Constant(p.displacement.rows(), 6, std::numeric_limits<double>::quiet_NaN());
  p.element_results = structure_->element_results(*assembler_, u, v);
  return p;
}

}  // namespace impactfe
