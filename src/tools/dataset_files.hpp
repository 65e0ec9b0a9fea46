#pragma once
// The files `generate` writes for one scenario, by format (docs/datasets.md): their names in one
// place, for the writers, the run's summary and the free-space check of the files a run replaces.
#include <string>
#include <vector>

namespace bearing_sim::tool {

// The plain formats' files: the measured channels, the ideal acceleration and the JSON sidecar
// (`<stem>_csv.json` for CSV, so that both formats can sit in one directory).
inline std::string dataset_vibration_path(const std::string& stem, const std::string& extension) {
  return stem + "_vibration." + extension;
}
inline std::string dataset_ideal_path(const std::string& stem, const std::string& extension) {
  return stem + "_vibration_ideal." + extension;
}
inline std::string dataset_sidecar_path(const std::string& stem, const std::string& extension) {
  return stem + (extension == "csv" ? "_csv.json" : ".json");
}

// Every file of one format ("bag", "npy" or "csv") for the scenario's stem.
inline std::vector<std::string> dataset_files(const std::string& stem, const std::string& format) {
  if (format == "bag") return {stem + ".bag"};
  return {dataset_vibration_path(stem, format), dataset_ideal_path(stem, format), dataset_sidecar_path(stem, format)};
}

}  // namespace bearing_sim::tool
