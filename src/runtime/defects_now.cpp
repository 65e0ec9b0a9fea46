#include "bearing_sim/runtime/defects_now.hpp"

namespace bearing_sim::runtime {

std::vector<DefectNow> scenario_defects_at(const Scenario& scenario, double time_s) {
  std::vector<DefectNow> defects;
  for (const Spall& spall : scenario.spalls_at(time_s))
    defects.push_back(DefectNow{spall, Scenario::spall_width_at(spall, time_s), Scenario::spall_depth_at(spall, time_s),
                                time_s - spall.created_at_s});
  return defects;
}

}  // namespace bearing_sim::runtime
