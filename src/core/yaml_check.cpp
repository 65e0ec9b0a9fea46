#include "bearing_sim/core/yaml_check.hpp"

#include "yaml_reader.hpp"

namespace bearing_sim {

void check_yaml_file(const std::string& path, const std::string& what) {
  detail::load_yaml(detail::read_config_file(path, what), path);
}

}  // namespace bearing_sim
