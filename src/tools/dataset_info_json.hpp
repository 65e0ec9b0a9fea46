#pragma once
// The description of a generated dataset as JSON: the bag's /bearing/dataset_info and the
// header of the NPY/CSV sidecar carry the same text.
#include <nlohmann/json.hpp>

#include "bearing_sim/runtime/dataset_sink.hpp"

namespace bearing_sim::tool {

nlohmann::json dataset_info_json(const runtime::DatasetInfo& info);

}  // namespace bearing_sim::tool
