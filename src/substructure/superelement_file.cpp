// Superelement file I/O with the HDF5 C library. Matrices are stored row-major as
// [rows x cols] float64 datasets; DOF lists as node-id (int) + label (string) pairs.
#include "substructure/superelement_file.h"

#include <fmt/format.h>
#include <hdf5.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"

namespace impactfe {

namespace {

constexpr const char* kFormat = "impactfe superelement";
constexpr int kVersion = 1;

/// Owns an HDF5 id.
class H5 {
 public:
  explicit H5(hid_t id, const std::string& what) : id_(id) {
    if (id_ < 0) throw std::runtime_error("superelement file: cannot " + what);
  }
  ~H5() {
    if (id_ >= 0) H5Idec_ref(id_);
  }
  H5(const H5&) = delete;
  H5& operator=(const H5&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("superelement file: cannot " + what);
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m) {
  const RowMajor r = m;
  hsize_t dims[2] = {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())};
  H5 space(H5Screate_simple(2, dims, nullptr), "create dataspace " + name);
  H5 ds(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        "create " + name);
  if (m.size() > 0)
    check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.data()),
          "write " + name);
}

Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name) {
  H5 ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open " + name);
  H5 space(H5Dget_space(ds), "get dataspace of " + name);
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space) != 2) throw std::runtime_error(name + " is not 2-D");
  H5Sget_simple_extent_dims(space, dims, nullptr);
  RowMajor r(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (r.size() > 0)
    check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.data()), "read " + name);
  return r;
}

void write_ints(hid_t loc, const std::string& name, const std::vector<int>& v) {
  hsize_t dims[1] = {v.size()};
  H5 space(H5Screate_simple(1, dims, nullptr), "create dataspace " + name);
  H5 ds(H5Dcreate2(loc, name.c_str(), H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        "create " + name);
  if (!v.empty())
    check(H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "write " + name);
}

std::vector<int> read_ints(hid_t loc, const std::string& name) {
  H5 ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open " + name);
  H5 space(H5Dget_space(ds), "get dataspace of " + name);
  std::vector<int> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty())
    check(H5Dread(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "read " + name);
  return v;
}

H5 string_type() {
  H5 t(H5Tcopy(H5T_C_S1), "copy string type");
  check(H5Tset_size(t, H5T_VARIABLE), "set string size");
  check(H5Tset_cset(t, H5T_CSET_UTF8), "set string charset");
  return H5(H5Tcopy(t), "copy string type");
}

void write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& v) {
  H5 type = string_type();
  std::vector<const char*> p;
  for (const auto& s : v) p.push_back(s.c_str());
  hsize_t dims[1] = {v.size()};
  H5 space(H5Screate_simple(1, dims, nullptr), "create dataspace " + name);
  H5 ds(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        "create " + name);
  if (!v.empty())
    check(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), "write " + name);
}

std::vector<std::string> read_strings(hid_t loc, const std::string& name) {
  H5 type = string_type();
  H5 ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open " + name);
  H5 space(H5Dget_space(ds), "get dataspace of " + name);
  std::vector<char*> p(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)), nullptr);
  std::vector<std::string> out;
  if (p.empty()) return out;
  check(H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), "read " + name);
  for (char* s : p) out.emplace_back(s ? s : "");
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, p.data());
  return out;
}

void write_attribute(hid_t obj, const std::string& name, const std::string& value) {
  H5 type = string_type();
  H5 space(H5Screate(H5S_SCALAR), "create scalar space");
  H5 attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
          "create attribute " + name);
  const char* p = value.c_str();
  check(H5Awrite(attr, type, &p), "write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, double value) {
  H5 space(H5Screate(H5S_SCALAR), "create scalar space");
  H5 attr(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
          "create attribute " + name);
  check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) <= 0) return {};
  H5 type = string_type();
  H5 attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name);
  char* p = nullptr;
  check(H5Aread(attr, type, &p), "read attribute " + name);
  std::string s = p ? p : "";
  H5free_memory(p);
  return s;
}

double read_double_attribute(hid_t obj, const std::string& name) {
  H5 attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name);
  double v = 0.0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

void write_dofs(hid_t loc, const std::string& prefix, const std::vector<DofKey>& keys) {
  std::vector<int> nodes;
  std::vector<std::string> labels;
  for (const auto& k : keys) {
    nodes.push_back(k.node);
    labels.emplace_back(dof_name(k.dof));
  }
  write_ints(loc, prefix + "_node", nodes);
  write_strings(loc, prefix + "_dof", labels);
}

std::vector<DofKey> read_dofs(hid_t loc, const std::string& prefix) {
  const std::vector<int> nodes = read_ints(loc, prefix + "_node");
  const std::vector<std::string> labels = read_strings(loc, prefix + "_dof");
  if (nodes.size() != labels.size())
    throw std::runtime_error("superelement file: " + prefix + " node/dof lists differ in length");
  std::vector<DofKey> keys;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto dof = parse_dof_label(labels[i]);
    if (!dof) throw std::runtime_error("superelement file: bad DOF label " + labels[i]);
    keys.push_back({nodes[i], *dof});
  }
  return keys;
}

H5 create_group(hid_t loc, const std::string& name) {
  return H5(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            "create group " + name);
}

}  // namespace

std::vector<DofKey> SuperelementData::master_keys() const {
  std::vector<DofKey> keys;
  for (const auto& m : masters) keys.push_back(m.key);
  return keys;
}

void write_superelement(const std::string& path, const SuperelementData& d) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // libraries never print
  H5 file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create " + path);
  write_attribute(file, "format", kFormat);
  write_attribute(file, "version", static_cast<double>(kVersion));
  write_attribute(file, "name", d.name);
  write_attribute(file, "title", d.title);
  write_attribute(file, "matrices", static_cast<double>(d.matrices));
  write_attribute(file, "n_masters", static_cast<double>(d.n_masters()));
  write_attribute(file, "n_slaves", static_cast<double>(d.n_slaves()));
  write_attribute(file, "n_load_vectors", static_cast<double>(d.load_vectors.cols()));

  {
    H5 g = create_group(file, "masters");
    write_dofs(g, "master", d.master_keys());
    Eigen::MatrixXd x(d.n_masters(), 3), a(d.n_masters(), 3);
    for (int i = 0; i < d.n_masters(); ++i) {
      x.row(i) = d.masters[static_cast<std::size_t>(i)].x.transpose();
      a.row(i) = d.masters[static_cast<std::size_t>(i)].angles_deg.transpose();
    }
    write_matrix(g, "coordinates", x);
    write_matrix(g, "angles_deg", a);
  }
  {
    H5 g = create_group(file, "matrices");
    write_matrix(g, "K", d.stiffness);
    if (d.mass) write_matrix(g, "M", *d.mass);
    if (d.damping) write_matrix(g, "C", *d.damping);
  }
  {
    H5 g = create_group(file, "loads");
    write_attribute(g, "layout", "columns: load vectors (one per load step) / X Y Z");
    write_matrix(g, "load_vectors", d.load_vectors);
    write_matrix(g, "unit_acceleration", d.unit_acceleration);
  }
  {
    H5 g = create_group(file, "expansion");
    write_dofs(g, "slave", d.slaves);
    write_dofs(g, "constrained", d.constrained);
    write_matrix(g, "transformation", d.transformation);
    write_matrix(g, "load_correction", d.load_correction);
    write_matrix(g, "acceleration_correction", d.acceleration_correction);
    write_attribute(g, "model", d.model_text);
  }
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

SuperelementData read_superelement(const std::string& path, const SourceLocation& where) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (!std::filesystem::exists(path))
    throw InputError(where, fmt::format("superelement file {} does not exist", path));
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError(where, fmt::format("{} is not an HDF5 superelement file", path));
  try {
    H5 file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path);
    if (read_string_attribute(file, "format") != kFormat)
      throw InputError(where, fmt::format("{} is not an impactfe superelement file", path));
    SuperelementData d;
    d.name = read_string_attribute(file, "name");
    d.title = read_string_attribute(file, "title");
    d.matrices = static_cast<int>(read_double_attribute(file, "matrices"));
    {
      H5 g(H5Gopen2(file, "masters", H5P_DEFAULT), "open masters");
      const std::vector<DofKey> keys = read_dofs(g, "master");
      const Eigen::MatrixXd x = read_matrix(g, "coordinates");
      const Eigen::MatrixXd a = read_matrix(g, "angles_deg");
      for (std::size_t i = 0; i < keys.size(); ++i)
        d.masters.push_back({keys[i], x.row(int(i)).transpose(), a.row(int(i)).transpose()});
    }
    {
      H5 g(H5Gopen2(file, "matrices", H5P_DEFAULT), "open matrices");
      d.stiffness = read_matrix(g, "K");
      if (H5Lexists(g, "M", H5P_DEFAULT) > 0) d.mass = read_matrix(g, "M");
      if (H5Lexists(g, "C", H5P_DEFAULT) > 0) d.damping = read_matrix(g, "C");
    }
    {
      H5 g(H5Gopen2(file, "loads", H5P_DEFAULT), "open loads");
      d.load_vectors = read_matrix(g, "load_vectors");
      d.unit_acceleration = read_matrix(g, "unit_acceleration");
    }
    {
      H5 g(H5Gopen2(file, "expansion", H5P_DEFAULT), "open expansion");
      d.slaves = read_dofs(g, "slave");
      d.constrained = read_dofs(g, "constrained");
      d.transformation = read_matrix(g, "transformation");
      d.load_correction = read_matrix(g, "load_correction");
      d.acceleration_correction = read_matrix(g, "acceleration_correction");
      d.model_text = read_string_attribute(g, "model");
    }
    const int n = d.n_masters();
    if (d.stiffness.rows() != n || d.stiffness.cols() != n || (d.mass && d.mass->rows() != n) ||
        (d.damping && d.damping->rows() != n) || d.unit_acceleration.rows() != n ||
        d.transformation.rows() != d.n_slaves())
      throw InputError(where, fmt::format("superelement file {}: inconsistent sizes", path));
    return d;
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    throw InputError(where, fmt::format("{}: {}", path, e.what()));
  }
}

// ---- generation model as text --------------------------------------------------------------

std::string serialize_generation_model(const Model& model, bool lumped_mass,
                                       bool stress_stiffening) {
  std::ostringstream o;
  o.precision(17);
  o << "impactfe-model 1\n";
  o << "flags " << int(lumped_mass) << ' ' << int(stress_stiffening) << '\n';
  for (const auto& [id, n] : model.nodes)
    o << "node " << id << ' ' << n.x(0) << ' ' << n.x(1) << ' ' << n.x(2) << ' ' << n.angles_deg(0)
      << ' ' << n.angles_deg(1) << ' ' << n.angles_deg(2) << '\n';
  for (const auto& [id, t] : model.element_types) {
    o << "etype " << id << ' ' << t.ansys_name << ' ' << static_cast<int>(t.kind);
    for (int k = 1; k <= 18; ++k) o << ' ' << t.key(k);
    o << '\n';
  }
  for (const auto& [id, r] : model.real_sets) {
    o << "real " << id << ' ' << r.values.size();
    for (double v : r.values) o << ' ' << v;
    o << '\n';
  }
  for (const auto& [id, m] : model.materials) {
    o << "mat " << id << ' ' << m.props.size();
    for (const auto& [label, v] : m.props) o << ' ' << label << ' ' << v;
    o << '\n';
  }
  for (const auto& [id, s] : model.sections) {
    o << "section " << id << ' ' << s.type << ' ' << s.data.size();
    for (double v : s.data) o << ' ' << v;
    o << '\n';
  }
  for (const auto& [id, e] : model.elements) {
    o << "element " << id << ' ' << e.type << ' ' << e.real << ' ' << e.mat << ' ' << e.secnum
      << ' ' << e.nodes.size();
    for (int n : e.nodes) o << ' ' << n;
    o << '\n';
  }
  return o.str();
}

Model deserialize_generation_model(const std::string& text, bool& lumped_mass,
                                   bool& stress_stiffening) {
  Model model;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag)) continue;
    if (tag == "impactfe-model") continue;
    if (tag == "flags") {
      int a = 0, b = 0;
      s >> a >> b;
      lumped_mass = a != 0;
      stress_stiffening = b != 0;
    } else if (tag == "node") {
      Node n;
      s >> n.id >> n.x(0) >> n.x(1) >> n.x(2) >> n.angles_deg(0) >> n.angles_deg(1) >>
          n.angles_deg(2);
      model.nodes[n.id] = n;
    } else if (tag == "etype") {
      ElementType t;
      int kind = 0;
      s >> t.id >> t.ansys_name >> kind;
      t.kind = static_cast<ElementKind>(kind);
      for (int k = 1; k <= 18; ++k) s >> t.keyopt[static_cast<std::size_t>(k)];
      model.element_types[t.id] = t;
    } else if (tag == "real") {
      RealSet r;
      std::size_t n = 0;
      s >> r.id >> n;
      r.values.resize(n);
      for (auto& v : r.values) s >> v;
      model.real_sets[r.id] = r;
    } else if (tag == "mat") {
      Material m;
      std::size_t n = 0;
      s >> m.id >> n;
      for (std::size_t i = 0; i < n; ++i) {
        std::string label;
        double v = 0.0;
        s >> label >> v;
        m.props[label] = v;
      }
      model.materials[m.id] = m;
    } else if (tag == "section") {
      Section sec;
      std::size_t n = 0;
      s >> sec.id >> sec.type >> n;
      sec.data.resize(n);
      for (auto& v : sec.data) s >> v;
      model.sections[sec.id] = sec;
    } else if (tag == "element") {
      ElementRecord e;
      std::size_t n = 0;
      s >> e.id >> e.type >> e.real >> e.mat >> e.secnum >> n;
      e.nodes.resize(n);
      for (auto& v : e.nodes) s >> v;
      model.elements[e.id] = e;
    }
    if (s.fail())
      throw std::runtime_error(
          fmt::format("superelement file: model record {} is malformed: {}", line_no, line));
  }
  return model;
}

}  // namespace impactfe
