// Shared helpers of the selection, POST1, POST26 and *GET handlers (see post_support.h).
#include "deck/post_support.h"
#include "core/files.h"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "deck/element_forces.h"
#include "deck/modeling_helpers.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace fs = std::filesystem;

// ---- selection ------------------------------------------------------------------------------

std::vector<int> selected_nodes(const DeckReader& r) {
  return selected_ids(r.model.nodes, r.model.selection.nodes);
}

std::vector<int> selected_elements(const DeckReader& r) {
  return selected_ids(r.model.elements, r.model.selection.elements);
}

std::vector<int> require_selected_nodes(const DeckReader& r, const Command& c) {
  auto ids = selected_nodes(r);
  if (ids.empty())
    r.fail(c, r.model.nodes.empty() ? "no nodes are defined"
                                    : "no nodes are selected (NSEL / NSLE selected none)");
  return ids;
}

std::vector<int> require_selected_elements(const DeckReader& r, const Command& c) {
  auto ids = selected_elements(r);
  if (ids.empty())
    r.fail(c, r.model.elements.empty() ? "no elements are defined"
                                       : "no elements are selected (ESEL / ESLN selected none)");
  return ids;
}

std::optional<std::vector<int>> component_members(const DeckReader& r, const Command& c,
                                                  const std::string& name,
                                                  const std::string& entity) {
  const std::string key = to_upper(name);
  const auto it = r.model.components.find(key);
  if (it == r.model.components.end() || r.params.get(key)) return std::nullopt;
  if (it->second.entity != entity)
    r.fail(c,
           fmt::format("component {} holds {} entities, not {}", key, it->second.entity, entity));
  std::vector<int> out;
  for (int id : it->second.ids)
    if (entity == "NODE" ? r.model.nodes.count(id) != 0 : r.model.elements.count(id) != 0)
      out.push_back(id);
  return out;
}

std::vector<int> nodes_of_field(DeckReader& r, const Command& c, int field) {
  const std::string l = r.label(c, field);
  if (l == "ALL") return require_selected_nodes(r, c);
  if (auto members = component_members(r, c, l, "NODE")) {
    if (members->empty()) r.fail(c, fmt::format("component {} has no existing nodes", l));
    return *members;
  }
  const auto id = r.opt_int(c, field);
  if (!id) r.fail(c, fmt::format("field {}: node number missing", field));
  r.require_node(c, *id);
  return {*id};
}

Model solution_model(const DeckReader& r, const Command& c) {
  Model m = r.model;
  std::size_t dropped = 0;
  for (auto it = m.elements.begin(); it != m.elements.end();)
    if (r.model.selection.elements.selected(it->first)) {
      ++it;
    } else {
      it = m.elements.erase(it);
      ++dropped;
    }
  if (dropped > 0)
    r.warn(c, fmt::format("{} unselected element(s) are left out of the solution (ESEL; ALLSEL "
                          "before the solution to solve them all)",
                          dropped));
  return m;
}

// ---- results --------------------------------------------------------------------------------

PostState& post_state(DeckReader& r) {
  if (!r.post) r.post = std::make_shared<PostState>();
  return *r.post;
}

namespace {

std::vector<std::string> results_files_here() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::current_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.size() > 3 && name.ends_with(".h5") &&
        !name.ends_with(".sub.h5"))
      out.push_back(name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string locate_results(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  std::string solved;
  if (r.options.host != nullptr) solved = r.options.host->results_for_reading(r.job);
  if (!ps.file_command.empty()) return ps.file_command;
  if (!solved.empty()) return solved;
  if (!r.options.results_file.empty()) return r.options.results_file;
  // The thesis's second jobs: <case>_post.inp reads the results of <case>.inp (in ANSYS 4.2 the
  // post job found file12 of the analysis job in the same directory).
  const std::string& job = r.model.jobname;
  std::vector<std::string> tried;
  if (job.size() > 5 && to_upper(job.substr(job.size() - 5)) == "_POST")
    tried.push_back(job.substr(0, job.size() - 5) + ".h5");
  tried.push_back(job + ".h5");
  for (const auto& t : tried)
    if (file_exists(t)) return t;
  const auto here = results_files_here();
  if (here.size() == 1) return here.front();
  std::string list;
  for (const auto& h : here) list += (list.empty() ? "" : ", ") + h;
  r.fail(c, fmt::format("no results to read: nothing was solved, no FILE command or --results "
                        "option, no {} in {}{}",
                        fmt::join(tried, " or "), fs::current_path().string(),
                        here.empty() ? std::string(" (no *.h5 file there)")
                                     : " and several candidates: " + list));
}

/// A post-only deck has no model: MAPDL's POST1 takes the geometry from the results file.
void model_from_results(DeckReader& r, const ResultsReader& reader, const Command& c) {
  if (r.model.title.empty()) r.model.title = reader.title();
  const Eigen::MatrixXd x = reader.node_coordinates();
  for (std::size_t i = 0; i < reader.node_ids().size(); ++i) {
    Node n;
    n.id = reader.node_ids()[i];
    n.x = x.row(static_cast<Eigen::Index>(i)).transpose();
    r.model.nodes[n.id] = n;
  }
  for (const auto& e : reader.elements()) {
    if (r.model.element_types.count(e.type) == 0) {
      ElementType t;
      t.id = e.type;
      t.ansys_name = e.type_name;
      t.where = c.where;
      r.model.element_types[e.type] = t;
    }
    ElementRecord rec;
    rec.id = e.id;
    rec.type = e.type;
    rec.mat = e.mat;
    rec.real = e.real;
    rec.nodes = e.nodes;
    rec.where = c.where;
    r.model.elements[e.id] = rec;
  }
  Log::info("{}:{}: {}: model taken from the results file ({} nodes, {} elements)", c.where.file,
            c.where.line, c.name, r.model.nodes.size(), r.model.elements.size());
}

}  // namespace

std::string results_file_name(const std::string& fname, const std::string& ext) {
  // HIS: the time-history file of an explicit run (EDHTIME), whose points the job's file holds.
  const std::string e = to_upper(ext);
  if (e.empty() || e == "RST" || e == "RDSP" || e == "RFRQ" || e == "RTH" || e == "RMG" ||
      e == "HIS" || e == "H5")
    return fname + ".h5";
  return fname + "." + ext;
}

const ResultsReader& results(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (ps.reader && ps.generation == r.solutions) return *ps.reader;
  const std::string path = locate_results(r, c);
  try {
    ps.reader = std::make_unique<ResultsReader>(path);
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
  ps.path = path;
  ps.generation = r.solutions;
  ps.sets = result_sets(*ps.reader);
  if (r.model.nodes.empty()) model_from_results(r, *ps.reader, c);
  return *ps.reader;
}

const SetData& current_set(DeckReader& r, const Command& c) {
  const ResultsReader& reader = results(r, c);
  PostState& ps = post_state(r);
  if (ps.current && ps.current_generation == r.solutions) return *ps.current;
  if (ps.sets.empty())
    r.fail(c, fmt::format("the results file {} holds no data set (nothing solved yet?)", ps.path));
  try {
    make_current(r, read_set(reader, ps.sets.back()));
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
  return *ps.current;
}

void make_current(DeckReader& r, SetData data) {
  PostState& ps = post_state(r);
  ps.current = std::move(data);
  ps.current_generation = r.solutions;
  ps.result_axes.clear();
}

namespace {

/// A component of a nodal vector (U, ROT, V, A, reaction) in the results system RSYS,KCN
/// (MAPDL RSYS): the stored triad (nodal axes of the node, global when not rotated) is taken
/// to global, g = T_node s, and then to the axes of system KCN at the node's location, l = Aᵀ g
/// (A: radial, tangential, axial in a cylindrical system; on its axis the system axes). NaN
/// when none of the triad is stored; an absent component counts as 0.
double nodal_component_in_rsys(DeckReader& r, const SetData& data, int row, int node,
                               const NodalLabel& lab, int kcn) {
  const int base = lab.column < 3 ? 0 : 3;
  Vec3 stored;
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    const double v = nodal_value(data, row, NodalLabel{lab.dataset, base + k, false});
    any = any || std::isfinite(v);
    stored(k) = std::isfinite(v) ? v : 0.0;
  }
  if (!any) return std::numeric_limits<double>::quiet_NaN();
  const Node& n = r.model.node(node);
  const Vec3 global = n.axes() * stored;
  Mat3 axes;
  r.model.coordinate_systems.get(kcn).axes_at(n.x, axes);
  return (axes.transpose() * global)(lab.column - base);
}

/// True when `node` is one of an element's own nodes, which carry its DOFs: an orientation
/// node (BEAM188's K, BEAM189's L) or a node no element uses has none, and MAPDL lists 0 there.
bool node_has_dofs(const Model& model, int node) {
  for (const auto& [id, e] : model.elements) {
    const auto type = model.element_types.find(e.type);
    if (type == model.element_types.end()) continue;
    const std::size_t own = std::min(
        e.nodes.size(), static_cast<std::size_t>(element_type_descriptor(type->second).n_nodes));
    if (std::find(e.nodes.begin(), e.nodes.begin() + static_cast<std::ptrdiff_t>(own), node) !=
        e.nodes.begin() + static_cast<std::ptrdiff_t>(own))
      return true;
  }
  return false;
}

}  // namespace

double nodal_result(DeckReader& r, const Command& c, int node, const std::string& label) {
  const auto lab = parse_nodal_item(label);
  if (!lab)
    r.fail(c, fmt::format("unknown nodal result '{}' (UX..ROTZ, USUM, VX..VZ, AX..AZ, FX..MZ)",
                          label));
  const ResultsReader& reader = results(r, c);
  const SetData& data = current_set(r, c);
  const int row = node_row(reader.node_ids(), node);
  if (row < 0) r.fail(c, fmt::format("node {} is not in the results file {}", node, reader.path()));
  const std::optional<int>& rsys = post_state(r).rsys;
  if (rsys && lab->column >= 0) {
    if (!r.model.nodes.count(node))
      r.fail(c, fmt::format("RSYS,{}: node {} is not in the model", *rsys, node));
    const double v = nodal_component_in_rsys(r, data, row, node, *lab, *rsys);
    if (std::isfinite(v)) return v;
  }
  const double v = nodal_value(data, row, *lab);
  if (std::isfinite(v)) return v;
  if (data.reduced && lab->dataset != 'R')
    r.fail(c, fmt::format("{} of node {} was not computed by the reduced run (not a master DOF; "
                          "expand it: EXPASS or /STRESS)",
                          label, node));
  if (lab->dataset != 'R' && !nodal_row_written(data, lab->dataset, row) &&
      node_has_dofs(r.model, node))
    r.fail(c,
           fmt::format("{} of node {} is not in the current set: OUTRES did not write {} of "
                       "this node at this time",
                       label, node, lab->dataset == 'U' ? "NSOL" : std::string(1, lab->dataset)));
  // A DOF the node does not have or a node without DOFs (MAPDL lists 0), or a reaction of a
  // free DOF.
  return 0.0;
}

std::string element_type_name(const DeckReader& r, int element) {
  const auto e = r.model.elements.find(element);
  if (e == r.model.elements.end()) return "";
  const auto t = r.model.element_types.find(e->second.type);
  return t == r.model.element_types.end() ? "" : t->second.ansys_name;
}

VtkCell element_cell(const DeckReader& r, int element) {
  const ElementTypeDescriptor* d = find_element_type(element_type_name(r, element));
  return d != nullptr ? d->vtk_cell : VtkCell::PolyVertex;
}

namespace {

const std::array<const char*, 6> kTensorComponents = {"X", "Y", "Z", "XY", "YZ", "XZ"};

}  // namespace

bool is_tensor_item(const std::string& item) {
  const std::string it = to_upper(item);
  return it == "S" || it == "EPEL" || it == "EPPL" || it == "EPTO" || it == "EPTH" || it == "EPCR";
}

int tensor_direction(const std::string& comp) {
  const std::string k = to_upper(comp);
  for (std::size_t i = 0; i < kTensorComponents.size(); ++i)
    if (k == kTensorComponents[i]) return static_cast<int>(i);
  return -1;
}

double tensor_in_results_system(DeckReader& r, const Command& c, int element,
                                const std::string& item, const std::array<double, 6>& stored,
                                int direction, const Vec3& location) {
  const PostState& ps = post_state(r);
  const auto k = static_cast<std::size_t>(direction);
  if (ps.rsys_solution) return stored[k];
  const Mat3& A = element_result_axes(r, c, element);
  const bool global = !ps.rsys || *ps.rsys == 0;
  if (global && A == Mat3::Identity()) return stored[k];
  // σ_g = A σ_e Aᵀ (A: the element's result axes in global), then σ_r = Bᵀ σ_g B with B the
  // axes of RSYS,KCN at the location; a strain's engineering shears are twice the tensor's.
  const double shear = to_upper(item) == "S" ? 1.0 : 0.5;
  Mat3 t;
  t << stored[0], shear * stored[3], shear * stored[5], shear * stored[3], stored[1],
      shear * stored[4], shear * stored[5], shear * stored[4], stored[2];
  t = A * t * A.transpose();
  if (!global) {
    Mat3 B;
    r.model.coordinate_systems.get(*ps.rsys).axes_at(location, B);
    t = B.transpose() * t * B;
  }
  static constexpr int kRow[6] = {0, 1, 2, 0, 1, 0}, kCol[6] = {0, 1, 2, 1, 2, 2};
  const double v = t(kRow[direction], kCol[direction]);
  return direction < 3 ? v : v / shear;
}

std::optional<double> element_result(DeckReader& r, const Command& c, int element,
                                     const std::string& item, const std::string& comp) {
  const int direction = tensor_direction(comp);
  if (direction < 0 || !is_tensor_item(item))
    return stored_element_result(r, c, element, item, comp);
  // A stress or strain component: the element's tensor (absent components 0 in its axes: a
  // shell's SZ, SYZ, SXZ) rotated into the results system at the element's centroid.
  std::array<double, 6> stored{};
  std::optional<double> wanted;
  bool any = false;
  for (std::size_t i = 0; i < kTensorComponents.size(); ++i) {
    const auto v = stored_element_result(r, c, element, item, kTensorComponents[i]);
    if (static_cast<int>(i) == direction) wanted = v;
    any = any || v.has_value();
    stored[i] = v && std::isfinite(*v) ? *v : 0.0;
  }
  if (!any || (wanted && !std::isfinite(*wanted))) return wanted;
  return tensor_in_results_system(r, c, element, item, stored, direction,
                                  element_centroid(r, element));
}

std::string shell_location_column(DeckReader& r, const std::string& name) {
  const std::string& location = post_state(r).shell_location;
  const int layer = post_state(r).layer;
  if ((location == "TOP" && layer == 0) || name.size() <= 4 ||
      name.compare(name.size() - 4, 4, "_TOP") != 0)
    return name;
  // LAYER,N: the surface of layer N ("SX_L2_BOT", a layered shell's columns).
  if (layer > 0) return fmt::format("{}_L{}_{}", name.substr(0, name.size() - 4), layer, location);
  return name.substr(0, name.size() - 3) + location;
}

std::optional<double> stored_element_result(DeckReader& r, const Command& c, int element,
                                            const std::string& item, const std::string& comp) {
  if (to_upper(item) == "VOLU") return element_volume(r, c, element);
  const SetData& data = current_set(r, c);
  const std::string type_name = element_type_name(r, element);
  // SHELL,MID or BOT: a shell's S items at that surface instead of the top (MAPDL SHELL).
  const std::string& location = post_state(r).shell_location;
  const ElementTypeDescriptor* type = find_element_type(type_name);
  const int layer = post_state(r).layer;
  const std::string k = to_upper(comp);
  const bool principal =
      to_upper(item) == "S" && (k == "1" || k == "2" || k == "3" || k == "INT" || k == "EQV");
  // A principal value the element stores at the top only (SHELL181's SEQV): from the
  // components at the surface asked for, below.
  bool from_components = false;
  if ((location != "TOP" || layer > 0) && type != nullptr)
    if (const auto seq = find_result_sequence(*type, item, comp)) {
      if (const std::string column = shell_location_column(r, seq->name); column != seq->name) {
        const auto row = data.element_rows.find(element);
        if (row == data.element_rows.end()) return std::numeric_limits<double>::quiet_NaN();
        const ElementResultTable& table = data.point.element_results.at(row->second.first);
        const auto col = std::find(table.item_names.begin(), table.item_names.end(), column);
        if (col == table.item_names.end() && principal)
          from_components = true;
        else if (col == table.item_names.end())
          r.fail(c,
                 fmt::format("{} {} has no {} value at SHELL,{}{}", type_name, item, comp, location,
                             layer > 0 ? fmt::format(" of LAYER,{} (the S components of a layered "
                                                     "SHELL181 or SHELL281 section)",
                                                     layer)
                                       : std::string()));
        if (!from_components)
          return table.values(row->second.second,
                              static_cast<Eigen::Index>(col - table.item_names.begin()));
      }
    }
  const auto value = from_components ? std::optional<double>()
                                     : element_item(data, element, type_name, item, comp);
  if (value || !principal) return value;
  // Principal stresses of an element that gives only the components (shells: SX SY SXY at the
  // surface): the eigenvalues of the stress tensor, S1 ≥ S2 ≥ S3, SINT = S1 − S3 and the von
  // Mises SEQV (absent components are 0: a shell's SZ, SYZ, SXZ).
  const auto part = [&](const char* name) -> std::optional<double> {
    return element_result(r, c, element, "S", name);
  };
  const auto sx = part("X");
  if (!sx) return value;
  const double sy = part("Y").value_or(0.0), sz = part("Z").value_or(0.0);
  const double sxy = part("XY").value_or(0.0), syz = part("YZ").value_or(0.0),
               sxz = part("XZ").value_or(0.0);
  Eigen::Matrix3d t;
  t << *sx, sxy, sxz, sxy, sy, syz, sxz, syz, sz;
  const Eigen::Vector3d p =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(t, Eigen::EigenvaluesOnly).eigenvalues();
  const double s1 = p(2), s2 = p(1), s3 = p(0);
  if (k == "1") return s1;
  if (k == "2") return s2;
  if (k == "3") return s3;
  if (k == "INT") return s1 - s3;
  return std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
}

std::optional<double> element_volume(DeckReader& r, const Command& c, int element) {
  const auto e = r.model.elements.find(element);
  if (e == r.model.elements.end()) r.fail(c, fmt::format("element {} is not defined", element));
  const ElementBuildContext context{
      r.model, [&](const ElementRecord& rec) -> std::string {
        throw InputError(c.where, fmt::format("element {}: the volume of a superelement is not "
                                              "available",
                                              rec.id));
      }};
  try {
    return create_element(context, e->second)->volume();
  } catch (const InputError& err) {
    r.fail(c, fmt::format("element {}: volume not available ({})", element, err.what()));
  }
}

Vec3 element_centroid(const DeckReader& r, int element) {
  const ElementRecord& e = r.model.elements.at(element);
  std::vector<int> distinct;
  for (int n : e.nodes)
    if (std::find(distinct.begin(), distinct.end(), n) == distinct.end()) distinct.push_back(n);
  Vec3 sum = Vec3::Zero();
  for (int n : distinct) sum += r.model.node(n).x;
  return sum / static_cast<double>(distinct.size());
}

// ---- printing -------------------------------------------------------------------------------

std::string listing_number(double v, int width) {
  std::string s;
  const double a = std::fabs(v);
  if (!std::isfinite(v)) {
    s = "NaN";
  } else if (a == 0.0) {
    s = "0.0000";
  } else if (a >= 0.1 && a < 99999.5) {
    const int before = a < 1.0 ? 0 : static_cast<int>(std::floor(std::log10(a))) + 1;
    s = fmt::format("{:.{}f}", v, std::max(0, 5 - before));
    // Rounding up may add a digit (9.99996 → 10.0000): redo with one decimal less.
    if (before > 0 &&
        static_cast<int>(std::floor(std::log10(std::fabs(std::stod(s))))) + 1 > before)
      s = fmt::format("{:.{}f}", v, std::max(0, 4 - before));
  } else {
    // Fortran E format with a leading zero: 0.12346E-01.
    int exponent = static_cast<int>(std::floor(std::log10(a))) + 1;
    double mantissa = a / std::pow(10.0, exponent);
    if (std::round(mantissa * 1e5) >= 1e5) {
      mantissa /= 10.0;
      ++exponent;
    }
    s = fmt::format("{}0.{:05d}E{}{:02d}", v < 0 ? "-" : "",
                    static_cast<int>(std::round(mantissa * 1e5)), exponent < 0 ? '-' : '+',
                    std::abs(exponent));
  }
  if (static_cast<int>(s.size()) < width)
    s.insert(0, static_cast<std::size_t>(width) - s.size(), ' ');
  return s;
}

std::string set_heading(const SetData& d) {
  std::string out =
      fmt::format("  LOAD STEP={:6d}  SUBSTEP={:6d}\n", d.set.load_step, d.set.substep);
  if (d.set.mode > 0)
    out += fmt::format("   FREQ={}      LOAD CASE=   0\n", listing_number(d.frequency, 10));
  else
    out += fmt::format("   TIME={}      LOAD CASE=   0{}\n", listing_number(d.set.time, 10),
                       d.interpolated ? "   (interpolated)" : "");
  return out;
}

void print(DeckReader& r, const std::string& text) {
  write_output(r, text);
}

void write_graph(DeckReader& r, const Command& c, const std::vector<GraphCurve>& curves,
                 const GraphOptions& options) {
  PostState& ps = post_state(r);
  const std::string base = ps.show_name.empty() ? r.model.jobname : ps.show_name;
  const std::string path = fmt::format("{}{:03d}.svg", base, ps.n_pictures++);
  ps.picture.reset();
  try {
    write_text_file(path, xy_graph_svg(curves, options));
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
  Log::info("{}:{}: {}: graph {}", c.where.file, c.where.line, c.name, path);
}

}  // namespace impactfe::deck
