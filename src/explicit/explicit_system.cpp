#include "explicit/explicit_system.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>

#include "elements/element_registry.h"

namespace impactfe {

bool runs_explicit(const Model& model, std::string* why_not) {
  if (model.elements.empty()) return false;
  for (const auto& [id, record] : model.elements) {
    const ElementTypeDescriptor& d = element_type_descriptor(model.element_type(record.type));
    if (!d.explicit_set) {
      if (why_not)
        *why_not = fmt::format("element {} is a {}, which has no explicit formulation", id, d.name);
      return false;
    }
  }
  return true;
}

bool has_explicit_elements(const Model& model) {
  for (const auto& [id, type] : model.element_types)
    if (element_type_descriptor(type).explicit_set) return true;
  return false;
}

std::size_t ExplicitSystem::n_elements() const {
  std::size_t n = 0;
  for (const auto& s : sets) n += s->size();
  return n;
}

int ExplicitSystem::index_of(int node_id) const {
  const auto it = std::lower_bound(node_ids.begin(), node_ids.end(), node_id);
  return it != node_ids.end() && *it == node_id ? static_cast<int>(it - node_ids.begin()) : -1;
}

void ExplicitSystem::update_inertia() {
  if (!has_rotations()) return;
  inertia.assign(n_nodes(), 0.0);
  for (const auto& set : sets) set->add_rotary_inertia(inertia);
}

namespace {

void number_nodes(const Model& model, ExplicitSystem& s) {
  std::set<int> used;
  for (const auto& [id, record] : model.elements)
    for (int n : record.nodes)
      if (n != 0) used.insert(n);
  s.node_ids.assign(used.begin(), used.end());
  for (int id : s.node_ids) {
    const auto it = model.nodes.find(id);
    const Vec3 p = it == model.nodes.end() ? Vec3::Zero() : it->second.x;
    s.x0.push_back(p.x());
    s.y0.push_back(p.y());
    s.z0.push_back(p.z());
  }
}

/// The node → slots lists: a counting sort of the slots by node, slots ascending per node.
void index_slots(ExplicitSystem& s) {
  s.slot_start.assign(s.n_nodes() + 1, 0);
  for (std::size_t i = 0; i < s.sets.size(); ++i) {
    const auto& set = *s.sets[i];
    for (std::size_t k = 0; k < set.size(); ++k)
      for (int a = 0; a < set.nodes_per_element(); ++a) ++s.slot_start[set.nodes(k)[a] + 1];
  }
  for (std::size_t n = 0; n < s.n_nodes(); ++n) s.slot_start[n + 1] += s.slot_start[n];
  s.slots.resize(s.slot_start.back());
  std::vector<std::size_t> fill(s.slot_start.begin(), s.slot_start.end() - 1);
  for (std::size_t i = 0; i < s.sets.size(); ++i) {
    const auto& set = *s.sets[i];
    const int per = set.nodes_per_element();
    for (std::size_t k = 0; k < set.size(); ++k)
      for (int a = 0; a < per; ++a)
        s.slots[fill[set.nodes(k)[a]]++] = s.set_offset[i] + k * per + a;
  }
}

/// The material whose rigid body the elements of each rigid material join: itself, or the end
/// of its chain of EDCRB master parts. A merged part that is not rigid, a body merged into two
/// masters and a cycle of merges are refused, located at the EDCRB command.
std::map<int, int> rigid_body_materials(const ExplicitControls& e) {
  std::map<int, int> master;  // slave material → master material, one step
  for (const auto& [neqn, m] : e.rigid_merges) {
    for (const auto& [part, mat] :
         {std::pair{m.master_part, m.master_material}, std::pair{m.slave_part, m.slave_material}})
      if (e.rigid_materials.count(mat) == 0)
        throw InputError(m.where, fmt::format("EDCRB equation {}: part {} (material {}) is not a "
                                              "rigid body (EDMP,RIGID,{})",
                                              neqn, part, mat, mat));
    if (m.slave_material == m.master_material) continue;  // parts of one material: one body
    const auto [it, inserted] = master.emplace(m.slave_material, m.master_material);
    if (!inserted && it->second != m.master_material)
      throw InputError(m.where,
                       fmt::format("EDCRB equation {}: the rigid body of material {} is already "
                                   "merged into that of material {}",
                                   neqn, m.slave_material, it->second));
  }
  // A chain from a merge's master back to its slave closes a cycle: refused at the first
  // equation (in NEQN order) of the cycle.
  for (const auto& [neqn, m] : e.rigid_merges) {
    int r = m.master_material;
    for (std::size_t hops = 0; hops <= master.size() && master.count(r); ++hops) {
      if (r == m.slave_material) break;
      r = master.at(r);
    }
    if (r == m.slave_material && m.slave_material != m.master_material)
      throw InputError(m.where,
                       fmt::format("EDCRB equation {}: merging the rigid body of material {} "
                                   "into that of material {} closes a cycle of merges",
                                   neqn, m.slave_material, m.master_material));
  }
  std::map<int, int> root;
  for (const auto& entry : e.rigid_materials) {
    int r = entry.first;
    while (master.count(r)) r = master.at(r);
    root[entry.first] = r;
  }
  return root;
}

/// One body per rigid material, or per group of them that EDCRB merges (`body_material`: each
/// rigid material's body): its nodes (those of its elements, and so also the nodes deformable
/// elements share with it), mass, centre and inertia. A node of two bodies that are not merged
/// is refused.
void build_rigid_bodies(const Model& model, const std::map<int, std::set<int>>& rigid_nodes,
                        const std::map<int, int>& body_material, ExplicitSystem& s) {
  if (rigid_nodes.empty()) return;
  s.rigid_body_of.assign(s.n_nodes(), -1);
  std::vector<double> rigid_mass(s.n_nodes(), 0.0);
  for (const auto& set : s.rigid_sets) set->add_lumped_mass(rigid_mass);
  const ExplicitNodalView initial{s.x0.data(), s.y0.data(), s.z0.data()};
  for (const auto& [mat, ids] : rigid_nodes) {
    const ExplicitRigidMaterial& m = model.explicit_dynamics.rigid_materials.at(mat);
    RigidBody body;
    body.material = mat;
    body.fixed_translation = rigid_constraint_axes(m.translation);
    body.fixed_rotation = rigid_constraint_axes(m.rotation);
    for (const auto& [member, root] : body_material)
      if (root == mat) body.materials.push_back(member);
    for (int id : ids) {
      const auto n = static_cast<std::size_t>(s.index_of(id));
      if (s.rigid_body_of[n] >= 0)
        throw InputError(
            m.where,
            fmt::format("node {} belongs to the rigid bodies of materials {} and {}: merge them "
                        "with EDCRB or keep their nodes apart",
                        id, s.rigid_bodies[static_cast<std::size_t>(s.rigid_body_of[n])].material,
                        mat));
      s.rigid_body_of[n] = static_cast<int>(s.rigid_bodies.size());
      body.nodes.push_back(n);
    }
    // S = ∫ρ x xᵀ of the body's elements, plus the mass that deformable elements sharing its
    // nodes put there, as points.
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const auto& set : s.rigid_sets)
      for (std::size_t k = 0; k < set->size(); ++k)
        if (body_material.at(model.elements.at(set->element_id(k)).mat) == mat)
          second += set->second_mass_moment(initial, k);
    for (std::size_t n : body.nodes) {
      const Eigen::Vector3d x(s.x0[n], s.y0[n], s.z0[n]);
      second += (s.mass[n] - rigid_mass[n]) * x * x.transpose();
    }
    set_rigid_body_inertia(body, s.mass, s.x0, s.y0, s.z0, second);
    if (!(body.mass > 0.0))
      throw InputError(m.where,
                       fmt::format("the rigid body of material {} has no mass (MP,DENS)", mat));
    s.rigid_bodies.push_back(std::move(body));
  }
}

}  // namespace

ExplicitSystem build_explicit_system(const Model& model) {
  ExplicitSystem s;
  number_nodes(model, s);
  // The elements of one type form one set, in ascending element id; those of a rigid material
  // form sets of their own, kept apart from the force loop.
  const ExplicitControls& e = model.explicit_dynamics;
  std::map<std::string, std::vector<const ElementRecord*>> by_type, rigid_by_type;
  const std::map<int, int> body_material = rigid_body_materials(e);
  std::map<int, std::set<int>> rigid_nodes;  // body's material → node ids
  for (const auto& [id, record] : model.elements) {
    if (const std::string why = esys_refusal(model, record); !why.empty())
      throw InputError(record.where, fmt::format("element {}: {}", id, why));
    const std::string& type = model.element_type(record.type).ansys_name;
    if (e.rigid_materials.count(record.mat)) {
      rigid_by_type[type].push_back(&record);
      // The element's own nodes: an orientation node (BEAM161's and LINK160's K, often one
      // for many elements) is not part of the body.
      const auto own =
          std::min(record.nodes.size(),
                   static_cast<std::size_t>(
                       element_type_descriptor(model.element_type(record.type)).n_nodes));
      for (std::size_t a = 0; a < own; ++a)
        if (record.nodes[a] != 0) rigid_nodes[body_material.at(record.mat)].insert(record.nodes[a]);
    } else {
      by_type[type].push_back(&record);
    }
  }
  ExplicitBuildContext ctx{
      .model = model,
      .node_index =
          [&s, &model](int node, const ElementRecord& record) {
            const int index = s.index_of(node);
            if (index < 0 || !model.nodes.count(node))
              throw InputError(record.where,
                               fmt::format("element {}: node {} is not defined", record.id, node));
            return index;
          },
      .controls = e};
  for (const auto& [name, records] : by_type) {
    const ElementTypeDescriptor& d = *find_element_type(name);
    s.set_offset.push_back(s.n_slots);
    s.sets.push_back(d.explicit_set(ctx, records));
    s.n_slots +=
        s.sets.back()->size() * static_cast<std::size_t>(s.sets.back()->nodes_per_element());
  }
  for (const auto& [name, records] : rigid_by_type)
    s.rigid_sets.push_back(find_element_type(name)->explicit_set(ctx, records));
  s.mass.assign(s.n_nodes(), 0.0);
  for (const auto& set : s.sets) set->add_lumped_mass(s.mass);
  for (const auto& set : s.rigid_sets) set->add_lumped_mass(s.mass);
  for (double m : s.mass) s.physical_mass += m;
  build_rigid_bodies(model, rigid_nodes, body_material, s);
  index_slots(s);
  std::vector<std::uint8_t> rotational(s.n_nodes(), 0);
  for (const auto& set : s.sets)
    if (set->has_rotations())
      for (std::size_t k = 0; k < set->size(); ++k)
        for (int a = 0; a < set->nodes_per_element(); ++a) rotational[set->nodes(k)[a]] = 1;
  for (std::size_t n = 0; n < s.n_nodes(); ++n)
    if (rotational[n]) s.rotational_nodes.push_back(n);
  s.update_inertia();
  return s;
}

}  // namespace impactfe
