#pragma once
// Writes a generated dataset for the non-ROS world (docs/datasets.md): the measured
// (sensor) channels and the ideal acceleration as NPY (float32, one row per sample) or
// CSV, and a JSON sidecar with rates, channels and units, scenario, bearing, seed, sensor
// and the label time line.
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "bearing_sim/runtime/dataset_sink.hpp"
#include "npy_file.hpp"

namespace bearing_sim::tool {

class DatasetPlainWriter : public runtime::DatasetSink {
 public:
  enum class Format { Npy, Csv };
  // Files `<stem>_vibration.<ext>`, `<stem>_vibration_ideal.<ext>` and `<stem>.json` (or
  // `<stem>_csv.json` for CSV, so that both formats can sit in one directory): dataset_files.hpp.
  DatasetPlainWriter(std::string stem, Format format);
  ~DatasetPlainWriter() override;

  void begin(const runtime::DatasetInfo& info) override;
  void ideal_chunk(const runtime::SampleChunk& chunk) override;
  void measured_chunk(const runtime::SampleChunk& chunk) override;
  void label(const runtime::LabelState& state) override;
  void end() override;

  std::string sidecar_path() const;

 private:
  struct Channel {  // one output file of x, y, z rows
    std::string path;
    double rate_hz = 0.0, first_time_s = 0.0;
    std::unique_ptr<NpyFloatWriter> npy;
    std::FILE* csv = nullptr;
    std::uint64_t rows = 0;
  };
  std::string extension() const;  // "npy" or "csv"
  void open(Channel& c, const std::string& path, std::uint64_t rows);
  void write(Channel& c, const runtime::SampleChunk& chunk);
  void close(Channel& c);

  std::string stem_;
  Format format_;
  runtime::DatasetInfo info_;
  Channel measured_, ideal_;
  nlohmann::json labels_;
};

}  // namespace bearing_sim::tool
