// Real-time factor of the dynamic model: simulated seconds per wall second on one core.
// BM_SimulateCtGantry is the figure of the README: the CT bearing (414 balls) under the
// paper's load at 10 kHz output with the converged internal step. --simd_target=AVX2 (or
// SSE4, ...) keeps the contact kernel off better targets; the context names the one that ran.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <iostream>
#include <string>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "bearing_sim/runtime/triaxial_sensor.hpp"
#include "reference_cases.hpp"

namespace {

using bearing_sim::Vector5;

bearing_sim::BearingConfig bearing(const std::string& file) {
  return bearing_sim::load_bearing_config(std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/" + file);
}

void simulate(benchmark::State& state, const bearing_sim::BearingConfig& config, const Vector5& load,
              double speed_rad_s, bearing_sim::IntegrationMethod method) {
  const bearing_sim::BearingModel model(config);
  bearing_sim::BearingDynamics dynamics(model, load, speed_rad_s, {10000.0, 0, true, method});
  constexpr int kSamplesPerIteration = 1000;  // 0.1 s simulated
  for (auto _ : state) {
    for (int i = 0; i < kSamplesPerIteration; ++i) benchmark::DoNotOptimize(dynamics.step());
  }
  const double simulated_s = state.iterations() * kSamplesPerIteration / dynamics.sample_rate_hz();
  state.counters["realtime_factor"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["substeps"] = dynamics.substeps();
  state.counters["balls"] = model.ball_count();
  // Balls integrated at the end (the rest are known clear of contact): the kernel's n.
  state.counters["active_balls"] = static_cast<double>(dynamics.active_ball_count());
}

using bearing_sim::IntegrationMethod;

Vector5 ct_load() {
  Vector5 load;
  load << 6800.0, 0.0, 0.0, 0.0, 2100.0;
  return load;
}

void BM_SimulateCtGantry(benchmark::State& state, IntegrationMethod method) {
  simulate(state, bearing("ct_gantry_lyc.yaml"), ct_load(), 180.0 * bearing_sim::kTwoPi / 60.0, method);
}

// The CT bearing with its rotor and its outer ring flexible (ct_gantry_flexible.yaml: 10 ring
// modes, 25 coordinates), same load and speed: FlexibleDynamics' automatic step.
void BM_SimulateCtGantryFlexible(benchmark::State& state, IntegrationMethod method) {
  const bearing_sim::BearingModel model(bearing("ct_gantry_flexible.yaml"));
  bearing_sim::FlexibleDynamics dynamics(bearing_sim::FlexibleBearing(model), ct_load(),
                                         180.0 * bearing_sim::kTwoPi / 60.0, 10000.0, 0, method);
  constexpr int kSamplesPerIteration = 1000;  // 0.1 s simulated
  for (auto _ : state) {
    for (int i = 0; i < kSamplesPerIteration; ++i) benchmark::DoNotOptimize(dynamics.step());
  }
  state.counters["realtime_factor"] =
      benchmark::Counter(state.iterations() * kSamplesPerIteration / 10000.0, benchmark::Counter::kIsRate);
  state.counters["substeps"] = dynamics.substeps();
}

// One linearization of the flexible ring's Adams method (docs/model.md 18.5: the static
// equilibrium of the load, the Jacobian, e^{hL} and the phi functions, the history's four
// remainders) and the step it precedes: the load moves by 30 % (beyond the 20 % rule) after
// the 15 samples the rule waits, which are not timed.
void BM_FlexibleLinearization(benchmark::State& state) {
  const bearing_sim::BearingModel model(bearing("ct_gantry_flexible.yaml"));
  bearing_sim::FlexibleDynamics dynamics(bearing_sim::FlexibleBearing(model), ct_load(),
                                         180.0 * bearing_sim::kTwoPi / 60.0);
  const std::uint64_t before = dynamics.linearizations();
  bool high = false;
  for (auto _ : state) {
    state.PauseTiming();
    for (int i = 1; i < bearing_sim::FlexibleDynamics::kSamplesPerLinearization; ++i) dynamics.step();
    high = !high;
    dynamics.set_load(high ? Vector5(1.3 * ct_load()) : ct_load());
    state.ResumeTiming();
    benchmark::DoNotOptimize(dynamics.step());
  }
  state.counters["linearizations_per_iteration"] =
      static_cast<double>(dynamics.linearizations() - before) / static_cast<double>(state.iterations());
}

// The CT bearing with waviness on both races and the balls, and a 2 mm x 20 um spall on
// the fixed inner race in the load zone.
bearing_sim::BearingConfig ct_gantry_with_defects() {
  return bearing_sim::test::ct_gantry_with_defects(BEARING_SIM_SOURCE_DIR);
}

void BM_SimulateCtGantryWithDefects(benchmark::State& state, IntegrationMethod method) {
  simulate(state, ct_gantry_with_defects(), ct_load(), 180.0 * bearing_sim::kTwoPi / 60.0, method);
}

// The same, with the node's triaxial housing accelerometer on every sample (the node's configuration).
void BM_SimulateCtGantryWithDefectsAndSensor(benchmark::State& state, IntegrationMethod method) {
  const bearing_sim::BearingModel model(ct_gantry_with_defects());
  bearing_sim::BearingDynamics dynamics(model, ct_load(), 180.0 * bearing_sim::kTwoPi / 60.0,
                                        {10000.0, 0, true, method});
  bearing_sim::runtime::TriaxialSensor sensor(
      bearing_sim::load_accelerometer_config(std::string(BEARING_SIM_SOURCE_DIR) +
                                             "/config/sensors/ct_gantry_housing_accelerometer.yaml"),
      dynamics.sample_rate_hz());
  constexpr int kSamplesPerIteration = 1000;
  Eigen::Vector3d measured;
  for (auto _ : state) {
    for (int i = 0; i < kSamplesPerIteration; ++i) {
      if (sensor.push(dynamics.step(), &measured)) benchmark::DoNotOptimize(measured);
    }
  }
  const double simulated_s = state.iterations() * kSamplesPerIteration / dynamics.sample_rate_hz();
  state.counters["realtime_factor"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["substeps"] = dynamics.substeps();
}

void BM_SimulateIns61822(benchmark::State& state, IntegrationMethod method) {
  Vector5 load;
  load << 3400.0, 0.0, 1750.0, 0.0, 0.0;
  simulate(state, bearing("ins_618_22_db.yaml"), load, 60.0 * bearing_sim::kTwoPi / 60.0, method);
}

// The 6205 deep-groove bearing of the health tests (9 balls, inner ring rotating at
// 1797 rpm) with a 1 mm x 20 um spall on the fixed outer race in the load zone.
void BM_SimulateDeepGroove6205WithSpall(benchmark::State& state, IntegrationMethod method) {
  bearing_sim::BearingConfig config = bearing("deep_groove_6205.yaml");
  config.imperfections = bearing_sim::imperfections_from_string(
      "imperfections: {}\ndefects: [{surface: outer_race, position_deg: 0, width_mm: 1.0, depth_um: 20}]", "bench",
      config.rows);
  Vector5 load;
  load << 1000.0, 0.0, 0.0, 0.0, 0.0;
  simulate(state, config, load, 1797.0 * bearing_sim::kTwoPi / 60.0, method);
}

}  // namespace

// Each case with the default integrator, and for comparison the others: ETDRK4, the
// exponential Adams predictor-corrector (PECE and PEC), classical RK4 at its converged step.
constexpr IntegrationMethod kDefault = bearing_sim::DynamicsOptions{}.method;
BENCHMARK_CAPTURE(BM_SimulateCtGantry, default, kDefault)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefects, default, kDefault)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefectsAndSensor, default, kDefault)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateIns61822, default, kDefault)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateDeepGroove6205WithSpall, default, kDefault)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantry, etdrk4, IntegrationMethod::ExponentialRk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefects, etdrk4, IntegrationMethod::ExponentialRk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateIns61822, etdrk4, IntegrationMethod::ExponentialRk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateDeepGroove6205WithSpall, etdrk4, IntegrationMethod::ExponentialRk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantry, adams, IntegrationMethod::ExponentialAdams)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefects, adams, IntegrationMethod::ExponentialAdams)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateIns61822, adams, IntegrationMethod::ExponentialAdams)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateDeepGroove6205WithSpall, adams, IntegrationMethod::ExponentialAdams)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantry, adams_pec, IntegrationMethod::ExponentialAdamsPec)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefects, adams_pec, IntegrationMethod::ExponentialAdamsPec)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateIns61822, adams_pec, IntegrationMethod::ExponentialAdamsPec)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateDeepGroove6205WithSpall, adams_pec, IntegrationMethod::ExponentialAdamsPec)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantry, rk4, IntegrationMethod::Rk4)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryFlexible, adams_pec, IntegrationMethod::ExponentialAdamsPec)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK(BM_FlexibleLinearization)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryFlexible, rk4, IntegrationMethod::Rk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateCtGantryWithDefects, rk4, IntegrationMethod::Rk4)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

// Takes --simd_target=NAME out of the arguments and limits the dispatch to it (an AVX2-only
// CPU's figures on an AVX-512 machine). False for a target this CPU cannot run.
bool apply_simd_target_flag(int* argc, char** argv) {
  const std::string flag = "--simd_target=";
  int kept = 1;
  bool ok = true;
  for (int i = 1; i < *argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(flag, 0) != 0) {
      argv[kept++] = argv[i];
    } else if (!bearing_sim::limit_simd_target(arg.substr(flag.size()))) {
      std::cerr << "bench_simulate: SIMD target '" << arg.substr(flag.size())
                << "' is not compiled in or this CPU cannot run it\n";
      ok = false;
    }
  }
  *argc = kept;
  return ok;
}

// Figures mean little without the CPU and the SIMD code path that produced them.
int main(int argc, char** argv) {
  if (!apply_simd_target_flag(&argc, argv)) return 1;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("cpu", bearing_sim::cpu_model_name());
  benchmark::AddCustomContext("simd_target", bearing_sim::simd_target_name());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
