#pragma once
// The spalls present at an instant with their size then: what the health report, the
// scenario labels and the ROS DefectState message carry.
#include <vector>

#include "bearing_sim/core/imperfections.hpp"
#include "bearing_sim/core/scenario.hpp"

namespace bearing_sim::runtime {

struct DefectNow {
  Spall spall;           // as injected (created_at_s on simulated time)
  double width_m = 0.0;  // now, with growth
  double depth_m = 0.0;
  double age_s = 0.0;
};

// The spalls of a scenario at time_s, sized by its growth law.
std::vector<DefectNow> scenario_defects_at(const Scenario& scenario, double time_s);

}  // namespace bearing_sim::runtime
