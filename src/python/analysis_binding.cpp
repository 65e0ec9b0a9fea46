// The analyser on a numpy signal (the core's analyze_vibration, as `bearing_tool analyze`)
// and the rigid-body modes on bearing stiffness (solve_modes, as `bearing_tool modes`).
#include <pybind11/stl.h>

#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/modal_analysis.hpp"
#include "binding_common.hpp"

namespace bearing_sim::python {
namespace {

py::dict analyze(const PyBearing& b, py::array_t<double, py::array::c_style | py::array::forcecast> signal,
                 double sample_rate_hz, double inner_rad_s, double outer_rad_s, double window_s, double resonance_hz,
                 double band_width_hz) {
  if (signal.ndim() != 1)
    throw InvalidInputError("signal: expected a 1-D array of accelerations (m/s^2), got " +
                            std::to_string(signal.ndim()) + " dimensions");
  std::vector<double> x(signal.data(), signal.data() + signal.size());
  const BearingFrequencies f = bearing_frequencies(*b.model, inner_rad_s, outer_rad_s);
  AnalysisOptions o;
  o.window_s = window_s;
  o.resonance_hz = resonance_hz;
  o.envelope_band_width_hz = band_width_hz;
  ConditionIndicators c;
  {
    py::gil_scoped_release release;
    c = analyze_vibration(x, sample_rate_hz, f, o);
  }
  py::dict d;
  d["samples"] = c.samples;
  d["window_s"] = c.window_s;
  d["rms_m_s2"] = c.acceleration.rms;
  d["peak_m_s2"] = c.acceleration.peak;
  d["crest_factor"] = c.acceleration.crest_factor;
  d["kurtosis"] = c.acceleration.kurtosis;
  d["level_db"] = c.level_db;
  d["velocity_rms_mm_s"] = c.velocity_rms_mm_s;
  d["velocity_band_hz"] = py::make_tuple(c.velocity_low_hz, c.velocity_high_hz);
  d["velocity_zone"] = velocity_zone_name(c.zone);
  d["envelope_band_hz"] = py::make_tuple(c.envelope_low_hz, c.envelope_high_hz);
  d["envelope_mean_m_s2"] = c.envelope_mean_m_s2;
  d["envelope_band_source"] = c.envelope_band_source;
  d["envelope_band_kurtosis"] = c.envelope_band_kurtosis;
  d["envelope_band_independent_samples"] = c.envelope_band_independent_samples;
  d["envelope_resolution_hz"] = c.envelope.resolution_hz;
  d["envelope_source"] = c.envelope_source;
  d["speed_measured"] = c.speed_measured;
  d["speed_scale"] = c.speed_scale;
  d["envelope_segments"] = c.envelope_segments;
  d["envelope_segment_s"] = c.envelope_segment_s;
  d["fault_snr_db_used"] = c.fault_snr_db_used;
  d["evidence_snr_db_used"] = c.evidence_snr_db_used;
  d["envelope_m_s2"] =
      py::array_t<double>(static_cast<py::ssize_t>(c.envelope.amplitude.size()), c.envelope.amplitude.data());
  py::list faults;
  for (const FaultIndicator& fi : c.faults) {
    py::dict e;
    e["fault"] = fault_kind_name(fi.kind);
    e["label"] = fault_frequency_label(fi.kind);
    e["expected_hz"] = fi.envelope_peak.expected_hz;
    e["frequency_hz"] = fi.envelope_peak.frequency_hz;
    e["amplitude_m_s2"] = fi.envelope_peak.amplitude;
    e["noise_floor_m_s2"] = fi.envelope_peak.noise_floor;
    e["snr_db"] = fi.envelope_peak.snr_db;
    e["chance"] = fi.envelope_peak.chance;
    e["modulation"] = fi.modulation;
    py::list harmonics, sidebands;
    for (const EvidenceLine& h : fi.harmonics)
      harmonics.append(py::make_tuple(h.peak.frequency_hz, h.peak.snr_db, h.found, h.shared, h.peak.chance));
    for (const EvidenceLine& s : fi.sidebands)
      sidebands.append(py::make_tuple(s.peak.frequency_hz, s.peak.snr_db, s.found));
    e["harmonics"] = harmonics;  // (frequency_hz, snr_db, found, shared, chance) of harmonics 1..4
    e["harmonics_found"] = fi.harmonics_found;
    e["sidebands_required"] = fi.sidebands_required;
    e["modulation_hz"] = fi.modulation_hz;
    e["sidebands"] = sidebands;  // (frequency_hz, snr_db, found) at -f_mod, +f_mod
    e["sidebands_found"] = fi.sidebands_found;
    e["suspected"] = fi.suspected;
    e["resolvable"] = fi.resolvable;
    e["impulsiveness_required"] = fi.impulsiveness_required;
    e["impulsive"] = fi.impulsive;
    e["note"] = fi.note;
    if (fi.intervals.tested) {  // rule 14, the ball series
      py::dict iv;
      iv["period_s"] = fi.intervals.period_s;
      iv["impacts"] = fi.intervals.impacts;
      iv["in_window"] = fi.intervals.in_window;
      iv["around"] = fi.intervals.around;
      iv["expected"] = fi.intervals.expected;
      iv["chance"] = fi.intervals.chance;
      iv["median_ratio"] = fi.intervals.median_ratio;
      iv["found"] = fi.intervals.found;
      e["impact_intervals"] = iv;
    }
    faults.append(e);
  }
  d["faults"] = faults;
  d["health"] = health_level_name(c.diagnosis.level);
  d["reason"] = c.diagnosis.reason;
  py::dict verdict;
  verdict["outcome"] = verdict_outcome_name(c.diagnosis.verdict.outcome);
  py::list kinds;
  for (FaultKind k : c.diagnosis.verdict.kinds) kinds.append(fault_kind_name(k));
  verdict["kinds"] = kinds;
  verdict["text"] = c.diagnosis.verdict.text;
  d["verdict"] = verdict;
  return d;
}

py::list modes(double mass_kg, const std::vector<double>& inertia, const py::sequence& supports, bool zero_angular) {
  if (inertia.size() != 3)
    throw InvalidInputError("inertia_kg_m2: expected 3 principal moments (Ixx, Iyy, Izz), got " +
                            std::to_string(inertia.size()));
  RigidBody body;
  body.mass_kg = mass_kg;
  body.inertia_kg_m2 = Eigen::Vector3d(inertia[0], inertia[1], inertia[2]);
  std::vector<BushingSupport> s;
  for (std::size_t i = 0; i < supports.size(); ++i) {
    const auto pair = supports[i].cast<py::sequence>();
    if (pair.size() != 2)
      throw InvalidInputError("supports[" + std::to_string(i) + "]: expected (stiffness 5x5, position_m 3)");
    const auto k = pair[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
    const auto p = pair[1].cast<std::vector<double>>();
    if (k.ndim() != 2 || k.shape(0) != 5 || k.shape(1) != 5 || p.size() != 3)
      throw InvalidInputError("supports[" + std::to_string(i) +
                              "]: expected a 5x5 stiffness (Bearing.static()['stiffness']) and a position (x, y, z) m");
    Matrix5 k5;
    for (int r = 0; r < 5; ++r)
      for (int c = 0; c < 5; ++c) k5(r, c) = k.at(r, c);
    s.push_back({bushing_matrix(k5), Eigen::Vector3d(p[0], p[1], p[2])});
  }
  ModalOptions o;
  o.zero_angular_stiffness = zero_angular;
  const ModalResult result = solve_modes(body, s, o);
  py::list out;
  for (const Mode& mode : result.modes) {
    py::dict d;
    d["frequency_hz"] = mode.frequency_hz;
    d["free"] = mode.free;
    d["shape"] = to_numpy(mode.shape);
    d["energy_fraction"] = to_numpy(mode.energy_fraction);
    d["dominant_dof"] = rigid_dof_name(mode.dominant_dof);
    out.append(d);
  }
  return out;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def("analyze", &analyze, py::arg("bearing"), py::arg("signal"), py::arg("sample_rate_hz"), py::arg("inner_rad_s"),
        py::arg("outer_rad_s"), py::arg("window_s") = 0.0, py::arg("resonance_hz") = 0.0,
        py::arg("band_width_hz") = 2000.0,
        "Condition indicators, envelope spectrum and diagnosis of an acceleration signal (m/s^2) recorded "
        "at the given ring speeds (docs/health.md); the GIL is released");
  m.def("modes", &modes, py::arg("mass_kg"), py::arg("inertia_kg_m2"), py::arg("supports"),
        py::arg("zero_angular_stiffness") = false,
        "Natural frequencies and mode shapes of a rigid body on bearings: supports is a list of "
        "(5x5 static stiffness, position of the bearing centre from the body's centre of mass, m)");
}

}  // namespace bearing_sim::python
