#pragma once
// A YAML file checked as the package's own files are read (src/core/yaml_reader.hpp), for
// files that others parse: the nodes' parameter files, which roslaunch loads with PyYAML
// (a key written twice: the last occurrence silently wins).
#include <string>

namespace bearing_sim {

// Throws ConfigError naming `path` for a file that is not a regular file of at most 1 MiB,
// malformed YAML, or a key written twice in one mapping (with the key and both lines).
// `what` names the kind of file in the message ("parameter file").
void check_yaml_file(const std::string& path, const std::string& what);

}  // namespace bearing_sim
