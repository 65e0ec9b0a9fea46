// Cost of the virtual accelerometer per input sample (ns), the figure that matters inside
// the real-time loop at 10..51.2 kHz: projection, path, noise, anti-alias, decimation, ADC.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/virtual_accelerometer.hpp"

namespace {

using bearing_sim::AccelerometerConfig;
using bearing_sim::DynamicSample;
using bearing_sim::VirtualAccelerometer;

// input_rate_hz / output rate from the config; mount on the moving ring adds a cos/sin.
void sensor(benchmark::State& state, AccelerometerConfig config, double input_rate_hz) {
  VirtualAccelerometer accelerometer(config, input_rate_hz);
  constexpr int kSamples = 4096;
  std::vector<DynamicSample> input(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double t = i / input_rate_hz;
    input[i].acceleration << std::sin(2000.0 * t), std::cos(3000.0 * t), 0.1 * std::sin(500.0 * t),
        0.01 * std::sin(700.0 * t), 0.02 * std::cos(900.0 * t);
    input[i].ring_angle_rad = 18.85 * t;
  }
  std::vector<double> output;
  output.reserve(kSamples);
  for (auto _ : state) {
    output.clear();
    accelerometer.push_block(input, &output);
    benchmark::DoNotOptimize(output.data());
  }
  // kIsRate | kInvert gives seconds per unit; counting in units of 1e-9 samples gives ns.
  state.counters["ns_per_input_sample"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSamples * 1e-9,
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SensorHousing10kHz(benchmark::State& state) { sensor(state, AccelerometerConfig{}, 10000.0); }

void BM_SensorMovingRing51k2To10k24(benchmark::State& state) {
  AccelerometerConfig c;
  c.mount = bearing_sim::SensorMount::MovingRing;
  c.output_rate_hz = 10240.0;
  sensor(state, c, 51200.0);
}

void BM_SensorNoNoise10kHz(benchmark::State& state) {
  AccelerometerConfig c;
  c.noise_density_m_s2_per_sqrt_hz = 0.0;
  sensor(state, c, 10000.0);
}

// The CWRU rig's sensor file: six path modes, 48 shaft harmonics, 3 half orders, 16 other
// orders, 6 line harmonics, the coloured floor (1201 taps at 12 kHz).
void BM_SensorCwruInstallation12kHz(benchmark::State& state) {
  sensor(state,
         bearing_sim::load_accelerometer_config(std::string(BEARING_SIM_SOURCE_DIR) +
                                                "/config/sensors/cwru_drive_end_accelerometer.yaml"),
         12000.0);
}

// The same with the fault records' rolling noise (132 ug/sqrt(Hz) at the ring; one Gaussian per
// input sample more).
void BM_SensorCwruInstallationRollingNoise12kHz(benchmark::State& state) {
  AccelerometerConfig c = bearing_sim::load_accelerometer_config(std::string(BEARING_SIM_SOURCE_DIR) +
                                                                 "/config/sensors/cwru_drive_end_accelerometer.yaml");
  c.installation.rolling_noise_m_s2_per_sqrt_hz = 132e-6 * bearing_sim::kStandardGravity_m_s2;
  sensor(state, c, 12000.0);
}

}  // namespace

BENCHMARK(BM_SensorHousing10kHz)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SensorMovingRing51k2To10k24)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SensorNoNoise10kHz)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SensorCwruInstallation12kHz)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SensorCwruInstallationRollingNoise12kHz)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
