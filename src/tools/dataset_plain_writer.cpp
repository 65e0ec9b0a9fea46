#include "dataset_plain_writer.hpp"

#include <fstream>
#include <stdexcept>

#include "dataset_files.hpp"
#include "dataset_info_json.hpp"

namespace bearing_sim::tool {

DatasetPlainWriter::DatasetPlainWriter(std::string stem, Format format) : stem_(std::move(stem)), format_(format) {}

DatasetPlainWriter::~DatasetPlainWriter() {
  for (Channel* c : {&measured_, &ideal_})
    if (c->csv) std::fclose(c->csv);
}

std::string DatasetPlainWriter::extension() const { return format_ == Format::Npy ? "npy" : "csv"; }

std::string DatasetPlainWriter::sidecar_path() const { return dataset_sidecar_path(stem_, extension()); }

void DatasetPlainWriter::open(Channel& c, const std::string& path, std::uint64_t rows) {
  c.path = path;
  if (format_ == Format::Npy) {
    c.npy = std::make_unique<NpyFloatWriter>(c.path, rows, 3);
    return;
  }
  c.csv = std::fopen(c.path.c_str(), "w");
  if (!c.csv) throw std::runtime_error("cannot create " + c.path);
  std::fprintf(c.csv, "sample,time_s,accel_x,accel_y,accel_z\n");
}

void DatasetPlainWriter::begin(const runtime::DatasetInfo& info) {
  info_ = info;
  open(measured_, dataset_vibration_path(stem_, extension()), info.measured_samples);
  measured_.rate_hz = info.measured_rate_hz;
  measured_.first_time_s = (info.decimation_ratio - 1) / info.sample_rate_hz;
  open(ideal_, dataset_ideal_path(stem_, extension()), info.ideal_samples);
  ideal_.rate_hz = info.sample_rate_hz;
  labels_ = {{"time_s", nlohmann::json::array()},
             {"phase", nlohmann::json::array()},
             {"ring_speed_rad_s", nlohmann::json::array()},
             {"ring_angle_rad", nlohmann::json::array()},
             {"load", nlohmann::json::array()},
             {"defects", nlohmann::json::array()}};
}

void DatasetPlainWriter::write(Channel& c, const runtime::SampleChunk& chunk) {
  for (std::size_t i = 0; i < chunk.size(); ++i) {
    const float row[3] = {chunk.accel_x[i], chunk.accel_y[i], chunk.accel_z[i]};
    if (c.npy) {
      c.npy->write_row(row);
    } else {
      const std::uint64_t k = chunk.first_sample + i;
      // %.9g: a float32 read back is the same float32.
      std::fprintf(c.csv, "%llu,%.9f,%.9g,%.9g,%.9g\n", static_cast<unsigned long long>(k),
                   c.first_time_s + static_cast<double>(k) / c.rate_hz, row[0], row[1], row[2]);
    }
  }
  c.rows += chunk.size();
}

void DatasetPlainWriter::ideal_chunk(const runtime::SampleChunk& chunk) { write(ideal_, chunk); }
void DatasetPlainWriter::measured_chunk(const runtime::SampleChunk& chunk) { write(measured_, chunk); }

void DatasetPlainWriter::label(const runtime::LabelState& s) {
  labels_["time_s"].push_back(s.time_s);
  labels_["phase"].push_back(s.inputs.phase);
  labels_["ring_speed_rad_s"].push_back(s.inputs.ring_speed_rad_s);
  labels_["ring_angle_rad"].push_back(s.inputs.ring_angle_rad);
  labels_["load"].push_back(std::vector<double>(s.inputs.load.data(), s.inputs.load.data() + 5));
  nlohmann::json defects = nlohmann::json::array();
  for (const runtime::DefectNow& d : s.defects)
    defects.push_back({{"surface", surface_name(d.spall.surface)},
                       {"position_rad", d.spall.position_rad},
                       {"ball", d.spall.surface == Surface::Ball ? d.spall.ball : -1},
                       {"row", d.spall.surface == Surface::Ball ? -1 : d.spall.row},
                       {"width_m", d.width_m},
                       {"depth_m", d.depth_m},
                       {"width_growth_m_per_s", d.spall.width_growth_m_per_s},
                       {"depth_growth_m_per_s", d.spall.depth_growth_m_per_s},
                       {"age_s", d.age_s}});
  labels_["defects"].push_back(defects);
}

void DatasetPlainWriter::close(Channel& c) {
  if (c.npy) {
    c.npy->close();
  } else if (c.csv) {
    const bool ok = std::ferror(c.csv) == 0;
    const bool closed = std::fclose(c.csv) == 0;
    c.csv = nullptr;
    if (!ok || !closed) throw std::runtime_error("error writing " + c.path);
  }
}

void DatasetPlainWriter::end() {
  close(measured_);
  close(ideal_);
  nlohmann::json j = dataset_info_json(info_);
  auto file_name = [](const std::string& path) { return path.substr(path.find_last_of('/') + 1); };
  auto channel = [&](const Channel& c, const std::string& what, const std::string& unit) {
    return nlohmann::json{{"file", file_name(c.path)},
                          {"format", format_ == Format::Npy ? "npy float32, shape (samples, 3)"
                                                            : "csv: sample, time_s, accel_x, accel_y, accel_z"},
                          {"what", what},
                          {"columns", {"accel_x", "accel_y", "accel_z"}},
                          {"unit", unit},
                          {"frame", info_.frame_id},
                          {"sample_rate_hz", c.rate_hz},
                          {"samples", c.rows},
                          {"first_sample_time_s", c.first_time_s}};
  };
  j["channels"] = {
      {"vibration", channel(measured_,
                            info_.sensor_file.empty() ? "ideal acceleration of the rotating ring (no sensor)"
                                                      : "virtual sensor output (docs/sensor.md)",
                            info_.sensor_unit)},
      {"vibration_ideal", channel(ideal_, "ideal acceleration of the rotating ring", "m_s2")}};
  j["labels"] = labels_;
  std::ofstream out(sidecar_path());
  out << j.dump(1) << '\n';
  out.close();
  if (!out) throw std::runtime_error("error writing " + sidecar_path());
}

}  // namespace bearing_sim::tool
