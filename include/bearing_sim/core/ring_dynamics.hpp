#pragma once
// The dynamics behind one interface, whatever the rotating ring: rigid (BearingDynamics, 5
// coordinates) or flexible (FlexibleDynamics, its modes too; docs/model.md 18), chosen by the
// bearing file's flexible_ring block. What the per-sample pipeline (node, bearing_tool
// generate, scenarios, campaigns, Python) needs: samples of the ring's 5 rigid-body
// coordinates, the inputs between samples, defects, the ball loads.
#include <cstdint>
#include <memory>
#include <vector>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"

namespace bearing_sim {

class RingDynamics {
 public:
  virtual ~RingDynamics() = default;
  virtual std::unique_ptr<RingDynamics> clone() const = 0;

  // One output sample (DynamicSample: the rigid-body coordinates x, y, z, theta_x, theta_y of
  // the rotating ring; a flexible ring's modes are in flexible_state()). Throws DivergenceError
  // on a non-finite state; reset_to_equilibrium then starts again.
  virtual const DynamicSample& step() = 0;
  virtual const DynamicSample& current() const = 0;
  // Inputs from the next sample on; InvalidInputError when not finite (see BearingDynamics).
  virtual void set_load(const Vector5& load) = 0;
  virtual void set_load(const Vector5& load_over_sample, const Vector5& load_at_sample_end) = 0;
  virtual void set_ring_speed(double ring_speed_rad_s) = 0;
  // Replace the bearing (clearance, damping, temperature) keeping the state; a flexible ring
  // stays flexible and a rigid one rigid (InvalidInputError otherwise).
  virtual void set_model(BearingModel model) = 0;
  virtual void add_spall(Spall spall) = 0;
  virtual void clear_spalls() = 0;
  virtual void reset_to_equilibrium() = 0;

  virtual const BearingModel& model() const = 0;
  virtual const Vector5& load() const = 0;
  virtual double ring_speed_rad_s() const = 0;
  virtual double sample_rate_hz() const = 0;
  virtual double substeps() const = 0;
  virtual double internal_step_s() const = 0;
  virtual IntegrationMethod method() const = 0;
  // The balls' loads at the current sample (with the ring's deformation for a flexible ring).
  virtual std::vector<BallState> ball_states() const = 0;
  // The flexible ring's full state (null for a rigid ring).
  virtual const FlexibleSample* flexible_state() const { return nullptr; }
  // The wrapped dynamics (null when the other kind).
  virtual BearingDynamics* rigid() { return nullptr; }
  virtual FlexibleDynamics* flexible() { return nullptr; }
};

// The rigid ring's BearingDynamics, as it is.
class RigidRingDynamics final : public RingDynamics {
 public:
  explicit RigidRingDynamics(BearingDynamics dynamics) : d_(std::move(dynamics)) {}
  std::unique_ptr<RingDynamics> clone() const override { return std::make_unique<RigidRingDynamics>(*this); }
  const DynamicSample& step() override {
    d_.step();
    return d_.current();
  }
  const DynamicSample& current() const override { return d_.current(); }
  void set_load(const Vector5& load) override { d_.set_load(load); }
  void set_load(const Vector5& mid, const Vector5& end) override { d_.set_load(mid, end); }
  void set_ring_speed(double speed) override { d_.set_ring_speed(speed); }
  void set_model(BearingModel model) override { d_.set_model(std::move(model)); }
  void add_spall(Spall spall) override { d_.add_spall(spall); }
  void clear_spalls() override { d_.clear_spalls(); }
  void reset_to_equilibrium() override { d_.reset_to_equilibrium(); }
  const BearingModel& model() const override { return d_.model(); }
  const Vector5& load() const override { return d_.load(); }
  double ring_speed_rad_s() const override { return d_.ring_speed_rad_s(); }
  double sample_rate_hz() const override { return d_.sample_rate_hz(); }
  double substeps() const override { return d_.substeps(); }
  double internal_step_s() const override { return d_.internal_step_s(); }
  IntegrationMethod method() const override { return d_.method(); }
  std::vector<BallState> ball_states() const override {
    return d_.model().ball_states(d_.current().displacement, d_.current().cage_angle_rad);
  }
  BearingDynamics* rigid() override { return &d_; }

 private:
  BearingDynamics d_;
};

// FlexibleDynamics with its samples' rigid-body coordinates as DynamicSample.
class FlexibleRingDynamics final : public RingDynamics {
 public:
  explicit FlexibleRingDynamics(FlexibleDynamics dynamics);
  std::unique_ptr<RingDynamics> clone() const override { return std::make_unique<FlexibleRingDynamics>(*this); }
  const DynamicSample& step() override;
  const DynamicSample& current() const override { return current_; }
  void set_load(const Vector5& load) override;
  void set_load(const Vector5& mid, const Vector5& end) override;
  void set_ring_speed(double speed) override { d_.set_ring_speed(speed); }
  void set_model(BearingModel model) override;
  void add_spall(Spall spall) override;
  void clear_spalls() override;
  void reset_to_equilibrium() override;
  const BearingModel& model() const override { return d_.bearing().model(); }
  const Vector5& load() const override { return d_.load(); }
  double ring_speed_rad_s() const override { return d_.ring_speed_rad_s(); }
  double sample_rate_hz() const override { return d_.sample_rate_hz(); }
  double substeps() const override { return d_.substeps(); }
  double internal_step_s() const override { return d_.internal_step_s(); }
  IntegrationMethod method() const override { return d_.method(); }
  std::vector<BallState> ball_states() const override {
    return d_.bearing().ball_states(d_.current().coordinates, d_.current().phase);
  }
  const FlexibleSample* flexible_state() const override { return &d_.current(); }
  FlexibleDynamics* flexible() override { return &d_; }

 private:
  void copy_sample();
  FlexibleDynamics d_;
  DynamicSample current_;
};

// The dynamics of `model`'s ring: FlexibleRingDynamics when its file has a flexible_ring
// block (integrator adams_pec or rk4; options.substeps as FlexibleDynamics'), else
// BearingDynamics. Throws as their constructors.
std::unique_ptr<RingDynamics> make_ring_dynamics(BearingModel model, const Vector5& load, double ring_speed_rad_s,
                                                 DynamicsOptions options = {});

}  // namespace bearing_sim
