#pragma once
// Shared pieces of the Python module bearing_sim._core: numpy conversions of the core's
// Eigen types. One file per group of bindings (bearing, scenario, analysis).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::python {

namespace py = pybind11;

// A copy of an Eigen matrix as a float64 numpy array (vectors 1-D, matrices row-major 2-D).
template <typename Derived>
py::array_t<double> to_numpy(const Eigen::MatrixBase<Derived>& m) {
  if (m.cols() == 1) {
    py::array_t<double> a(static_cast<py::ssize_t>(m.rows()));
    for (Eigen::Index i = 0; i < m.rows(); ++i) a.mutable_at(i) = m(i, 0);
    return a;
  }
  py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) a.mutable_at(r, c) = m(r, c);
  return a;
}

// The Python Bearing: shared and immutable, so that runs in several Python threads may
// use one bearing at once.
struct PyBearing {
  std::shared_ptr<const BearingModel> model;
  std::string source;
};

// (Fx, Fy, Fz, Mx, My) from a force (3) and a moment (2); throws InvalidInputError for a
// wrong length.
Vector5 make_load(const std::vector<double>& force_N, const std::vector<double>& moment_Nm);

void bind_bearing(py::module_& m);
void bind_scenario(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace bearing_sim::python
