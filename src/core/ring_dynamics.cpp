#include "bearing_sim/core/ring_dynamics.hpp"

#include <string>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

FlexibleRingDynamics::FlexibleRingDynamics(FlexibleDynamics dynamics) : d_(std::move(dynamics)) { copy_sample(); }

void FlexibleRingDynamics::copy_sample() {
  const FlexibleSample& s = d_.current();
  current_.time_s = s.time_s;
  current_.cage_angle_rad = s.phase.cage;
  current_.ring_angle_rad = d_.bearing().ring_angle_rad(s.phase);
  current_.displacement = s.coordinates.head<5>();
  current_.velocity = s.velocities.head<5>();
  current_.acceleration = s.accelerations.head<5>();
}

const DynamicSample& FlexibleRingDynamics::step() {
  d_.step();
  copy_sample();
  return current_;
}

void FlexibleRingDynamics::set_load(const Vector5& load) {
  d_.set_load(load);
  copy_sample();  // the current acceleration moves with the load
}

void FlexibleRingDynamics::set_load(const Vector5& mid, const Vector5& end) {
  d_.set_load(mid, end);
  copy_sample();
}

void FlexibleRingDynamics::set_model(BearingModel model) {
  d_.set_model(std::move(model));
  copy_sample();
}

void FlexibleRingDynamics::add_spall(Spall spall) {
  d_.add_spall(spall);
  copy_sample();
}

void FlexibleRingDynamics::clear_spalls() {
  d_.clear_spalls();
  copy_sample();
}

void FlexibleRingDynamics::reset_to_equilibrium() {
  d_.reset_to_equilibrium();
  copy_sample();
}

std::unique_ptr<RingDynamics> make_ring_dynamics(BearingModel model, const Vector5& load, double ring_speed_rad_s,
                                                 DynamicsOptions options) {
  if (!model.config().flexible_ring.present)
    return std::make_unique<RigidRingDynamics>(BearingDynamics(std::move(model), load, ring_speed_rad_s, options));
  return std::make_unique<FlexibleRingDynamics>(FlexibleDynamics(FlexibleBearing(std::move(model)), load,
                                                                 ring_speed_rad_s, options.sample_rate_hz,
                                                                 options.substeps, options.method));
}

}  // namespace bearing_sim
