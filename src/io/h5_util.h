#pragma once
/// Thin RAII helpers over the HDF5 C API shared by the results file and the superelement file.
#include <hdf5.h>
#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace impactfe::h5 {

/// Owns one HDF5 identifier of any kind and releases it (H5Idec_ref) when destroyed.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      o.id_ = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0) H5Idec_ref(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
};

/// Silences the HDF5 error stack printer: libraries never print; failures become exceptions.
/// Also keeps HDF5 from installing its shutdown at exit (see h5_util.cpp).
void silence_errors();

/// The system's reason for the last HDF5 failure ("No space left on device"), or HDF5's
/// innermost message; "" when the error stack is empty.
std::string last_error_reason();

/// A failed HDF5 call: "cannot <what>: <reason>" (callers add the file name).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what);
};

/// Throws Error when id < 0.
hid_t check(hid_t id, const std::string& what);
void check_status(herr_t status, const std::string& what);

bool exists(hid_t loc, const std::string& name);

Handle create_group(hid_t loc, const std::string& name);
Handle open_group(hid_t loc, const std::string& name);

/// Variable-length UTF-8 string datatype.
Handle string_type();

void write_attribute(hid_t obj, const std::string& name, double value);
void write_attribute(hid_t obj, const std::string& name, const std::string& value);
void write_attribute(hid_t obj, const std::string& name, const std::vector<std::string>& values);

std::string read_string_attribute(hid_t obj, const std::string& name);
double read_double_attribute(hid_t obj, const std::string& name);
std::vector<std::string> read_string_list_attribute(hid_t obj, const std::string& name);
/// Names of all attributes of an object in creation/name order.
std::vector<std::string> attribute_names(hid_t obj);

/// Fixed-size dataset (row-major data, dims as given). Zero-sized datasets are allowed.
void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const double* data);
void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const int* data);
void write_dataset(hid_t loc, const std::string& name, const std::vector<std::string>& values);

/// Current dimensions of a dataset.
std::vector<hsize_t> dims_of(hid_t dataset);

std::vector<double> read_doubles(hid_t loc, const std::string& name);
/// A 2-D float64 dataset (row-major in the file) as a matrix.
Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name);
void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m);
std::vector<int> read_ints(hid_t loc, const std::string& name);
std::vector<std::string> read_strings(hid_t loc, const std::string& name);

/// Reads the hyperslab [start, start+count) of a dataset into a dense row-major buffer.
std::vector<double> read_slab(hid_t dataset, const std::vector<hsize_t>& start,
                              const std::vector<hsize_t>& count);

}  // namespace impactfe::h5
