// One build's side of dev/compare_builds.sh: the bench_simulate cases behind a C interface,
// so that two builds of the core library can be loaded side by side into one process
// (dlmopen) and timed in turns. Built by the script against each build; not part of the package.
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "reference_cases.hpp"

namespace {

volatile double benchmark_sink = 0.0;  // written by each timed loop, so that it is not optimized away

using bearing_sim::BearingConfig;
using bearing_sim::Vector5;

struct Case {
  bearing_sim::BearingModel model;
  bearing_sim::BearingDynamics dynamics;
  Case(const BearingConfig& config, const Vector5& load, double rpm)
      : model(config), dynamics(model, load, rpm * 2.0 * 3.14159265358979 / 60.0, {10000.0, 0, true}) {}
};

Vector5 load5(double fx, double fy, double fz, double mx, double my) {
  Vector5 load;
  load << fx, fy, fz, mx, my;
  return load;
}

}  // namespace

extern "C" {

int paired_case_count() { return 4; }

const char* paired_case_name(int which) {
  static const char* const kNames[] = {"CT gantry bearing", "CT with waviness and spall", "INS 618/22 pair",
                                       "6205 with a spall"};
  return kNames[which];
}

// The case's dynamics (bench_simulate's default cases but the sensor), on `simd_target`.
void* paired_make_case(int which, const char* source_dir, const char* simd_target) {
  bearing_sim::limit_simd_target(simd_target);
  const std::string bearings = std::string(source_dir) + "/config/bearings/";
  const Vector5 ct = load5(6800.0, 0.0, 0.0, 0.0, 2100.0);
  switch (which) {
    case 0:
      return new Case(bearing_sim::load_bearing_config(bearings + "ct_gantry_lyc.yaml"), ct, 180.0);
    case 1:
      return new Case(bearing_sim::test::ct_gantry_with_defects(source_dir), ct, 180.0);
    case 2:
      return new Case(bearing_sim::load_bearing_config(bearings + "ins_618_22_db.yaml"),
                      load5(3400.0, 0.0, 1750.0, 0.0, 0.0), 60.0);
    default: {
      // The spall appended to the file's text: bearing_config_from_string is in the base
      // commits' headers as well (the driver is built against both trees).
      std::ifstream in(bearings + "deep_groove_6205.yaml");
      std::stringstream text;
      text << in.rdbuf()
           << "\nimperfections: {}\ndefects: [{surface: outer_race, position_deg: 0, width_mm: 1.0, depth_um: 20}]\n";
      return new Case(bearing_sim::bearing_config_from_string(text.str(), "paired"), load5(1000.0, 0.0, 0.0, 0.0, 0.0),
                      1797.0);
    }
  }
}

// CPU time per sample of `samples` samples, ns.
double paired_step(void* handle, int samples) {
  auto* c = static_cast<Case*>(handle);
  timespec start, end;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &start);
  double sink = 0.0;
  for (int i = 0; i < samples; ++i) sink += c->dynamics.step().acceleration[0];
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &end);
  benchmark_sink = sink;
  return ((end.tv_sec - start.tv_sec) * 1e9 + (end.tv_nsec - start.tv_nsec)) / samples;
}

const char* paired_simd_target() {
  static std::string name;
  name = bearing_sim::simd_target_name();
  return name.c_str();
}
}
