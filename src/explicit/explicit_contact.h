#pragma once
/// Penalty contact of an explicit run (EDCGEN; docs/explicit_dynamics.md, "Contact"), after the
/// LS-DYNA Theory Manual ("Contact-impact algorithm", "Penalty method"): a slave node found
/// behind a master segment by g > 0 is pushed out by k·g along the segment's normal, the
/// reaction spread over the segment's nodes by its shape functions at the projection point;
/// k = SLSFAC·SF·K·A²/V of the segment (K the bulk modulus, A the face area, V the element
/// volume, SLSFAC 0.1). Friction: an elastic tangential spring of the same k whose force is
/// bounded by μ·f_n, μ = FD + (FS − FD)·exp(−DC·|v_rel|); optional viscous damping VDC (% of
/// critical). Surface to surface contact is two node-to-surface passes (symmetric); single
/// surface contact checks every exterior node against every exterior segment not next to it.
/// The gap is taken at the slave's projection point on the bilinear segment, so the force is
/// the gradient of ½kg²; a slave keeps the segment it came through while it stays behind it, and
/// a new contact must have crossed its segment over the step (the springs give back what they
/// took: an elastic impact keeps its energy).
///
/// The segments come from the element sets (ExplicitElementSet::segments): a face offered by two
/// elements is interior and dropped. The search is a bucket sort of the segments' boxes (one
/// sort, O(n log n)) redone only when a node has moved far enough since the last one to reach a
/// segment it was not listed against; the cycle loops the candidate lists (O(n)). Forces are
/// summed in a fixed order (slaves ascending, candidates ascending), so runs are repeatable.
#include <map>
#include <string>
#include <vector>

#include "core/model.h"
#include "explicit/explicit_interaction.h"
#include "explicit/explicit_system.h"

namespace impactfe {

class ExplicitContactSet final : public ExplicitInteraction {
 public:
  /// The contact definitions of `model` (InputError at the EDCGEN for a part or component that
  /// does not exist or offers no segment).
  ExplicitContactSet(const Model& model, const ExplicitSystem& system);
  bool empty() const { return passes_.empty(); }

  ExplicitStepLimit add_forces(const ExplicitNodalView& state, const double* mass, double time,
                               double dt, double* fx, double* fy, double* fz) override;
  double contact_energy() const override { return energy_; }
  /// Energy in the penalty springs now (normal and tangential): contact_energy() minus it is
  /// what friction and damping dissipated.
  double stored_energy() const { return stored_; }
  /// The resultant force on the contact surface (Cont of EDCGEN) of each contact entity in the
  /// last cycle, x, y, z per entity in EDCGEN order (LS-DYNA's RCFORC; the target surface
  /// takes the opposite force). NaN for a single surface contact, which has no sides.
  const std::vector<double>& interface_forces() const { return interface_force_; }
  /// A line for the run summary.
  std::string summary() const;
  long searches() const { return searches_; }

 private:
  struct Segment {
    int nodes[4];
    int element;
    double stiffness;  // K·A²/V (solid) or K·A/diagonal (shell), without the factors
    double depth;      // how far behind the face a node is still taken as penetrating
    double offset;     // a shell's half thickness: its two surfaces off the mid-surface (0)
  };
  /// One node-to-surface pass.
  struct Pass {
    const ExplicitContact* definition;
    std::size_t entity;     // the contact entity (EDCGEN order from 0)
    double interface_side;  // +1: slaves on the contact surface; −1: segments on it; 0: single
    double factor;          // SLSFAC × SFS or SFM
    bool single_surface;
    std::vector<std::size_t> slaves;    // run node indices, ascending
    std::vector<std::size_t> segments;  // indices into segments_, ascending
    /// Single surface: the nodes next to each slave (sorted CSR): segments holding one of them
    /// are not checked against it.
    std::vector<std::size_t> near_start;
    std::vector<int> near;
    std::vector<std::size_t> candidate_start;  // CSR per slave into candidates
    std::vector<std::size_t> candidates;       // indices into segments_
    std::vector<double> tangential;            // friction force on each slave (3 each)
    /// The segment each slave is in contact with (its index in segments_; none when out), and
    /// the side of it (±1 along its normal; a shell's back is −1).
    std::vector<std::size_t> kept;
    std::vector<signed char> side;
  };
  struct Projection;  // a slave's contact point on its segment (explicit_contact.cpp)

  // ---- set-up (the constructor) ----
  /// The exterior faces of the element sets as segments, their penalty stiffness and depth;
  /// the search margin.
  void collect_segments(const ExplicitSystem& system);
  /// The segments and the slave nodes of a surface named by a part number or a component
  /// (blank: the whole model).
  void surface(const Model& model, const ExplicitSystem& system, const std::map<int, int>& part,
               const ExplicitContact& k, const std::string& name, std::vector<std::size_t>& segs,
               std::vector<std::size_t>& nodes) const;
  /// One node-to-surface pass of `k`: `slaves` against `segs`, penalty factor `factor`.
  void add_pass(const ExplicitContact& k, double factor, bool single,
                std::vector<std::size_t> slaves, std::vector<std::size_t> segs, std::size_t n_nodes,
                std::size_t entity, double side);
  /// Single surface: the nodes of the segments around each slave of `p` (Pass::near).
  void list_near_nodes(Pass& p, std::size_t n_nodes) const;

  // ---- a cycle (add_forces) ----
  /// Whether some node has moved by a quarter of the margin since the last search.
  bool search_due(const ExplicitNodalView& s) const;
  /// A new search of every pass, and the step of the pairs it lists.
  void search_all(const ExplicitNodalView& s, const double* mass);
  void search(Pass& p, const ExplicitNodalView& s) const;
  bool shares_node(std::size_t a, std::size_t b) const;
  /// The segment slave j of `p` is in contact with (false when out of contact); updates kept.
  bool find_contact(Pass& p, std::size_t j, const ExplicitNodalView& s, bool on, double dt,
                    Projection& at) const;
  /// The penalty (normal, damping, friction) force of slave j on its segment `at`.
  void add_contact_force(Pass& p, std::size_t j, const ExplicitNodalView& s, const double* mass,
                         double dt, const Projection& at);
  void touch(std::size_t n, double fx, double fy, double fz);
  /// The contact energy and stable step of the cycle, and the forces onto f_int.
  void close_cycle(const ExplicitNodalView& s, const double* mass, double dt,
                   ExplicitStepLimit& limit, double* fx, double* fy, double* fz);
  std::vector<Segment> segments_;
  /// Half the thickness of the thickest shell at each node (0 off shells): a shell node as a
  /// slave touches a surface that far off its mid-surface.
  std::vector<double> node_offset_;
  std::vector<Pass> passes_;
  std::vector<double> x_search_, y_search_, z_search_;  // positions at the last search
  double margin_ = 0.0;                                 // box inflation of the search
  std::vector<double> force_, previous_;                // contact forces on the nodes (3 each)
  std::vector<double> stiffness_;  // Σ of the contact springs' row bounds at each node
  double potential_step_ = 0.0;    // the step of the pairs listed by the last search
  int potential_element_ = 0;
  int element_ = 0;  // an element in contact (named when the contact's step rules)
  std::vector<std::size_t> touched_, touched_before_;
  std::vector<std::uint8_t> mark_;
  std::vector<double> interface_force_;  // interface_forces()
  double energy_ = 0.0, stored_ = 0.0;
  long searches_ = 0;
  long active_ = 0, peak_active_ = 0;
  bool started_ = false;
};

}  // namespace impactfe
