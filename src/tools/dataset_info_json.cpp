#include "dataset_info_json.hpp"

namespace bearing_sim::tool {

nlohmann::json dataset_info_json(const runtime::DatasetInfo& info) {
  nlohmann::json j;
  j["generator"] = "bearing_tool generate";
  j["scenario"] = {{"name", info.scenario}, {"description", info.description}, {"file", info.scenario_file}};
  j["bearing"] = {{"name", info.bearing_name}, {"file", info.bearing_file}};
  j["sensor"] =
      info.sensor_file.empty()
          ? nlohmann::json(nullptr)
          : nlohmann::json{{"name", info.sensor_name}, {"file", info.sensor_file}, {"unit", info.sensor_unit}};
  j["seed"] = info.seed;
  j["duration_s"] = info.duration_s;
  j["sample_rate_hz"] = info.sample_rate_hz;
  j["measured_rate_hz"] = info.measured_rate_hz;
  j["decimation_ratio"] = info.decimation_ratio;
  j["ideal_samples"] = info.ideal_samples;
  j["measured_samples"] = info.measured_samples;
  j["label_rate_hz"] = info.label_rate_hz;
  j["frame_id"] = info.frame_id;
  j["simd_target"] = info.simd_target;
  nlohmann::json phases = nlohmann::json::array();
  for (const ScenarioPhase& p : info.phases) phases.push_back({{"name", p.name}, {"start_s", p.start_s}});
  j["phases"] = phases;
  return j;
}

}  // namespace bearing_sim::tool
