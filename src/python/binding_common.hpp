#pragma once
// Shared pieces of the Python module bearing_sim._core: numpy conversions of the core's
// Eigen types. One file per group of bindings (bearing, scenario, analysis).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_dynamics.hpp"
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

// Ctrl-C in a long call: the runs (simulate, generate) release the GIL, and their loop calls
// poll() (cheap: a clock read) for every sample or chunk; every ~0.1 s of wall time it takes the
// GIL back briefly for PyErr_CheckSignals. When a handler raised (KeyboardInterrupt), poll()
// throws Interrupted, which unwinds the run; the caller, holding the GIL again, rethrows the
// Python error: `catch (const SignalCheck::Interrupted&) { throw py::error_already_set(); }`.
class SignalCheck {
 public:
  struct Interrupted {};
  void poll() {
    const Clock::time_point now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_ = Clock::now();
};

// Wall time per output sample of the dynamics alone, from a short probe (200 samples or 0.2 s,
// as bearing_tool's measure_seconds_per_sample); 0 when the load is not carried (no estimate:
// the run itself reports it). Call with the GIL released.
double probe_seconds_per_sample(const BearingModel& model, const Vector5& load, double ring_speed_rad_s,
                                double sample_rate_hz, int substeps, IntegrationMethod method);

// bearing_tool's --allow-long-run for Python: a run of `samples` at `seconds_per_sample`
// estimated longer than kLongRunLimitS is refused (InvalidInputError naming the estimate, the
// limit and allow_long_run=True) unless `allow_long_run`; above kAnnounceRunS a UserWarning
// says the estimate. `what` names the call. Call with the GIL held.
void check_long_run(double samples, double seconds_per_sample, bool allow_long_run, const std::string& what);

void bind_bearing(py::module_& m);
void bind_scenario(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace bearing_sim::python
