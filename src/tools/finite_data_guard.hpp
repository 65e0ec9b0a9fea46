#pragma once
// The first sink of `bearing_tool generate`: stops a run before a sample that is not a finite
// number reaches the files (the writers come after it), naming the scenario, the stream, the
// channel and the sample. The run then fails (exit 1) instead of writing NaN with exit 0.
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bearing_sim/runtime/dataset_sink.hpp"

namespace bearing_sim::tool {

class FiniteDataGuard : public runtime::DatasetSink {
 public:
  explicit FiniteDataGuard(std::string scenario) : scenario_(std::move(scenario)) {}

  void begin(const runtime::DatasetInfo&) override {}
  void ideal_chunk(const runtime::SampleChunk& chunk) override { check(chunk, "vibration_ideal"); }
  void measured_chunk(const runtime::SampleChunk& chunk) override { check(chunk, "vibration"); }
  void level(std::uint64_t index, double accel_rms, double) override {
    if (!std::isfinite(accel_rms))
      fail("the vibration level at dynamics sample " + std::to_string(index) + " is not finite");
  }
  void label(const runtime::LabelState&) override {}
  void end() override {}

 private:
  void check(const runtime::SampleChunk& c, const char* stream) const {
    const std::pair<const char*, const std::vector<float>*> channels[] = {{"accel_x", &c.accel_x},
                                                                          {"accel_y", &c.accel_y},
                                                                          {"accel_z", &c.accel_z},
                                                                          {"displacement_x", &c.displacement_x},
                                                                          {"displacement_y", &c.displacement_y},
                                                                          {"displacement_z", &c.displacement_z},
                                                                          {"tilt_x", &c.tilt_x},
                                                                          {"tilt_y", &c.tilt_y}};
    for (const auto& [name, values] : channels)
      for (std::size_t i = 0; i < values->size(); ++i)
        if (!std::isfinite((*values)[i]))
          fail(std::string(stream) + " " + name + " at sample " + std::to_string(c.first_sample + i) +
               " is not a finite number (as float: beyond 3.4e38?)");
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("scenario '" + scenario_ + "': " + what +
                             "; the run was stopped, its files are incomplete");
  }

  std::string scenario_;
};

}  // namespace bearing_sim::tool
