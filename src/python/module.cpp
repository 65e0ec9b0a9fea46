// bearing_sim._core: the ROS-free core for Python (docs/python.md). The package
// bearing_sim re-exports it next to the generated messages (bearing_sim.msg).
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "binding_common.hpp"

namespace bearing_sim::python {

Vector5 make_load(const std::vector<double>& force_N, const std::vector<double>& moment_Nm) {
  if (force_N.size() != 3)
    throw InvalidInputError("force_N: expected 3 components (Fx, Fy, Fz), got " + std::to_string(force_N.size()));
  if (moment_Nm.size() != 2)
    throw InvalidInputError("moment_Nm: expected 2 components (Mx, My), got " + std::to_string(moment_Nm.size()));
  Vector5 load;
  load << force_N[0], force_N[1], force_N[2], moment_Nm[0], moment_Nm[1];
  return load;
}

}  // namespace bearing_sim::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace bearing_sim;
  m.doc() = "ROS-free bearing_sim core: bearings, equilibrium, dynamics, scenarios, analysis";
  // The core's errors keep their messages (file, key, value); all are ValueError or
  // RuntimeError so that generic handlers still catch them.
  py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  py::register_exception<LoadNotCarriedError>(m, "LoadNotCarriedError", PyExc_ValueError);
  py::register_exception<InvalidInputError>(m, "InvalidInputError", PyExc_ValueError);
  py::register_exception<DivergenceError>(m, "DivergenceError", PyExc_RuntimeError);
  m.def("cpu_model_name", &cpu_model_name, "The CPU model (for reporting speeds)");
  m.def("simd_target_name", &simd_target_name, "The SIMD target of the contact kernel on this CPU");
  python::bind_bearing(m);
  python::bind_scenario(m);
  python::bind_analysis(m);
}
