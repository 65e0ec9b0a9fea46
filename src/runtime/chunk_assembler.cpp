#include "bearing_sim/runtime/chunk_assembler.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace bearing_sim {
namespace runtime {

ChunkAssembler::ChunkAssembler(std::size_t chunk_samples, std::uint64_t first_sample)
    : chunk_samples_(chunk_samples), current_target_(chunk_samples), next_sample_(first_sample) {
  if (chunk_samples == 0) throw std::invalid_argument("a chunk must hold at least one sample");
  start_chunk();
}

void ChunkAssembler::set_chunk_samples(std::size_t chunk_samples) {
  if (chunk_samples == 0) throw std::invalid_argument("a chunk must hold at least one sample");
  chunk_samples_ = chunk_samples;
  if (chunk_.size() == 0) start_chunk();  // nothing collected yet: applies at once
}

void ChunkAssembler::start_chunk() {
  current_target_ = chunk_samples_;
  chunk_.first_sample = next_sample_;
  for (auto* v : {&chunk_.accel_x, &chunk_.accel_y, &chunk_.accel_z, &chunk_.displacement_x, &chunk_.displacement_y,
                  &chunk_.displacement_z, &chunk_.tilt_x, &chunk_.tilt_y}) {
    v->clear();
    v->reserve(current_target_);
  }
}

bool ChunkAssembler::add(std::uint64_t sample_index, const Eigen::Vector3d& acceleration, const Vector5& displacement) {
  if (sample_index != next_sample_)
    throw std::logic_error("chunk assembler: sample " + std::to_string(sample_index) + " is not the next one (" +
                           std::to_string(next_sample_) + ")");
  chunk_.accel_x.push_back(static_cast<float>(acceleration[0]));
  chunk_.accel_y.push_back(static_cast<float>(acceleration[1]));
  chunk_.accel_z.push_back(static_cast<float>(acceleration[2]));
  chunk_.displacement_x.push_back(static_cast<float>(displacement[0]));
  chunk_.displacement_y.push_back(static_cast<float>(displacement[1]));
  chunk_.displacement_z.push_back(static_cast<float>(displacement[2]));
  chunk_.tilt_x.push_back(static_cast<float>(displacement[3]));
  chunk_.tilt_y.push_back(static_cast<float>(displacement[4]));
  ++next_sample_;
  return chunk_.size() >= current_target_;
}

SampleChunk ChunkAssembler::take() {
  SampleChunk full = std::move(chunk_);
  chunk_ = SampleChunk{};
  start_chunk();
  return full;
}

}  // namespace runtime
}  // namespace bearing_sim
