#pragma once
// The description of a generated dataset as JSON: the bag's /bearing/dataset_info and the
// header of the NPY/CSV sidecar carry the same text.
#include <nlohmann/json.hpp>

#include "dataset_sink.hpp"

namespace bearing_sim::tool {

nlohmann::json dataset_info_json(const DatasetInfo& info);

}  // namespace bearing_sim::tool
