#pragma once
// 5-DOF dynamics of the moving ring on its Hertz contacts, integrated around the linearized
// contacts by an exponential Adams method (the default; its step need not divide the output
// sample) or exponential RK4 (ETDRK4), or by classical RK4, with an internal step no longer
// than the output sample period.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/integrator_state.hpp"

namespace bearing_sim {

struct DynamicSample {
  double time_s = 0.0;
  double cage_angle_rad = 0.0;
  double ring_angle_rad = 0.0;             // of the rotating ring
  Vector5 displacement = Vector5::Zero();  // x, y, z, theta_x, theta_y
  Vector5 velocity = Vector5::Zero();
  Vector5 acceleration = Vector5::Zero();
};

enum class IntegrationMethod {
  // Cox-Matthews ETDRK4: the linearized ring dynamics (stiffness and damping of the loaded
  // contacts) are integrated exactly by their matrix exponential, only the nonlinear
  // remainder explicitly; 4 force evaluations per internal step.
  ExponentialRk4,
  Rk4,  // classical RK4, 4 force evaluations per internal step
  // Exponential Adams predictor-corrector around the same linearization: the remainder
  // over a step is the cubic through its values at the starts of the last steps (ETD-AB4
  // predictor, ETD-AM4 corrector at the predicted end, PECE): 2 force evaluations per
  // internal step. The step need not divide the sample: the samples between step ends come
  // from the corrector's cubic. Its history is made by three ETDRK4 steps backward in time
  // (at the start, after a new linearization, model or defect).
  ExponentialAdams,
  // The same without the evaluation at the corrected end (PEC): 1 force evaluation per
  // internal step. The end's acceleration is the predicted end's moved by the linear part,
  // a_p + A (y_c - y_p), and the next step starts from the predicted end's remainder.
  ExponentialAdamsPec,
};

// The default: exponential Adams PEC, one force evaluation per internal step, within 1 % of
// a converged RK4 in a_rms on every studied case at its step rule (docs/model.md, 10.5).
constexpr IntegrationMethod kDefaultIntegrationMethod = IntegrationMethod::ExponentialAdamsPec;
// The names users type (node parameter ~integrator, bearing_tool --integrator): adams_pec,
// adams_pece, etdrk4, rk4.
const char* integration_method_name(IntegrationMethod method);
// Empty when `name` is none of them.
std::optional<IntegrationMethod> integration_method_from_name(const std::string& name);
std::vector<std::string> integration_method_names();

// The highest output sample rate of a run (node parameter, scenario sample_rate_hz,
// bearing_tool simulate --rate, bearing_sim.simulate): above, one second of run is hours of work.
constexpr double kMaxSampleRateHz = 1e6;
// Wall time of a run estimated before it starts (bearing_tool simulate / generate,
// bearing_sim.simulate / generate): longer than kAnnounceRunS it is announced, longer than
// kLongRunLimitS it needs the confirmation (--allow-long-run, allow_long_run=True).
constexpr double kAnnounceRunS = 600.0;
constexpr double kLongRunLimitS = 3600.0;

struct DynamicsOptions {
  double sample_rate_hz = 10000.0;
  // Internal steps per output sample; 0 chooses them from the highest natural
  // frequency at the static equilibrium (see choose_step_ratio).
  int substeps = 0;
  // Integrate only the balls within a safe margin of contact (results unchanged, since
  // a sample in which an excluded ball touches is redone with all balls).
  bool skip_clear_balls = true;
  IntegrationMethod method = kDefaultIntegrationMethod;
};

class BearingDynamics {
 public:
  // Starts at the static equilibrium under `load` (N, N*m on the moving ring) with the
  // rotating ring at `ring_speed_rad_s`. Throws LoadNotCarriedError if it cannot be carried.
  BearingDynamics(BearingModel model, const Vector5& load, double ring_speed_rad_s, DynamicsOptions options = {});

  // New inputs take effect from the next sample. Throw InvalidInputError if not finite.
  void set_load(const Vector5& load);
  // A load that moves within the next sample (a ramp, a rotating unbalance): the integration
  // follows the straight line through `load_over_sample` at the sample's middle (a driver
  // passes the mid-sample value) and `load_at_sample_end` at its end, so the sample's
  // reported acceleration is that of its end time. Holding the mid value for it would add
  // M^-1 dF/dt h/2, a spurious line proportional to the step (docs/model.md 7.5). After the
  // sample the load holds its end value until the next call.
  void set_load(const Vector5& load_over_sample, const Vector5& load_at_sample_end);
  void set_ring_speed(double ring_speed_rad_s);
  // Replace the bearing (clearance, damping, defects) keeping the state.
  void set_model(BearingModel model);

  // Advance one output sample. Throws DivergenceError on a non-finite or runaway state;
  // the state is then unchanged from before the call.
  DynamicSample step();
  // Spalls at runtime; a new spall starts growing now. add_spall throws InvalidInputError
  // for a defect that does not fit the bearing.
  void add_spall(Spall spall);
  void clear_spalls();
  // Back to the static equilibrium of the current load, at rest, keeping time and cage angle.
  void reset_to_equilibrium();

  const DynamicSample& current() const { return current_; }
  const RollingPhase& phase() const { return phase_; }
  const BearingModel& model() const { return model_; }
  const Vector5& load() const { return load_line_.load; }
  double ring_speed_rad_s() const { return ring_speed_; }
  double cage_speed_rad_s() const { return cage_speed_; }
  double sample_rate_hz() const { return options_.sample_rate_hz; }
  // Internal steps per output sample: an integer, or for the Adams methods in automatic mode
  // a multiple of 1/4 (e.g. 1.25: five steps per four samples).
  double substeps() const { return static_cast<double>(step_ratio_.steps) / step_ratio_.samples; }
  IntegrationMethod method() const { return options_.method; }
  double internal_step_s() const { return step_ratio_.samples / (options_.sample_rate_hz * step_ratio_.steps); }
  std::uint64_t sample_index() const { return sample_index_; }
  // Balls integrated in the last sample, and how often a sample had to be redone with
  // every ball because one outside the contact margin touched.
  std::size_t active_ball_count() const { return split_.active.size(); }
  std::uint64_t full_sample_retries() const { return split_.full_sample_retries; }

  // Natural frequencies of the ring on the linearized contacts at the static equilibrium.
  static Vector5 natural_frequencies_rad_s(const BearingModel& model, const Vector5& load);
  // Largest |eigenvalue| of the linearized ring dynamics with contact damping, rad/s.
  static double fastest_rate_rad_s(const BearingModel& model, const Vector5& load);
  // Internal steps per sample so that |lambda|_max * h <= kStepTimesOmegaMax (RK4) or
  // kExponentialStepTimesOmegaMax (the exponential integrators). Chosen at construction and
  // again (in automatic mode) when the model or the load changes a lot.
  static int choose_substeps(const BearingModel& model, const Vector5& load, double sample_rate_hz,
                             IntegrationMethod method = IntegrationMethod::Rk4);
  // `steps` internal steps per `samples` output samples. The Adams methods give the samples
  // between step ends from the corrector's cubic, so their step need not divide the sample:
  // the smallest multiple of 1/4 step per sample (at least 1) within the limit, e.g. 5 steps
  // per 4 samples instead of 2 per sample for the CT bearing (|lambda| h = 0.84 per sample).
  // With a spall or roughness (a remainder rough within a step) whole steps per sample.
  // The other methods: choose_substeps steps per sample.
  struct StepRatio {
    int steps = 1, samples = 1;
  };
  static StepRatio choose_step_ratio(const BearingModel& model, const Vector5& load, double sample_rate_hz,
                                     IntegrationMethod method);
  static constexpr int kAdamsStepSampleDivisions = integrators::kAdamsStepSampleDivisions;
  static constexpr double kStepTimesOmegaMax = 0.5;
  static constexpr double kExponentialStepTimesOmegaMax = 1.0;
  // The Adams methods extrapolate the remainder from past steps. Without spalls it is smooth
  // (varying compliance, waviness): at 0.7 every studied case is within 0.6 % of converged
  // RK4 in a_rms. A ball entering or leaving a spall makes it rough within a step: the
  // shipped 6205 with a 1 mm x 20 um outer-race spall is 2.2 % off at |lambda| h = 0.70,
  // 1.2 % at 0.63 and 0.2 % at 0.51; at 0.55 every studied spall is within 0.8 %
  // (docs/model.md, 10.3 and 10.5).
  static constexpr double kAdamsStepTimesOmegaMax = 0.7;
  static constexpr double kAdamsWithSpallStepTimesOmegaMax = 0.55;
  static double step_times_omega_max(IntegrationMethod method);
  // Linearizations of the exponential integrator since construction (it is redone when
  // the load has moved by more than kRelinearizeLoadChange of its size, at most every
  // kSamplesPerLinearization samples, or the model changed).
  std::uint64_t linearizations() const { return etd_.linearizations; }
  static constexpr double kRelinearizeLoadChange = 0.2;
  static constexpr int kSamplesPerLinearization = 16;  // at most one per this many samples

 private:
  using CageTrig = integrators::CageTrig;
  using Vector10 = integrators::Vector10;
  using Matrix10 = integrators::Matrix10;
  using AdamsState = integrators::AdamsState;
  Vector5 acceleration(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase,
                       const BallArrays& balls) const;
  Vector5 acceleration(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase, const BallArrays& balls,
                       const CageTrig& trig) const;
  RollingPhase advanced(const RollingPhase& phase, double dt) const;
  double slipping_cage_speed() const;
  // One output sample from the acceleration a_start: q, v and phase from the sample's start
  // to its end. The Adams methods advance `adams` past the sample's end and give the end's
  // acceleration in *a_end (returning true); the others leave its evaluation to the caller.
  bool integrate_sample(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start, const BallArrays& balls,
                        AdamsState& adams, Vector5* a_end) const;
  void integrate_sample_rk4(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                            const BallArrays& balls) const;
  void integrate_sample_exponential(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                                    const BallArrays& balls) const;
  // One ETDRK4 step of the stored weights' step (h, or -h for the Adams method's history)
  // from y with the remainder r1 at its start; `rotation`: the cage's turn in half of it.
  Vector10 etdrk4_step(const Vector10& y, const Vector5& r1, const RollingPhase& phase, const CageTrig& trig, double h,
                       const CageTrig& rotation, const BallArrays& balls) const;
  // The Adams method's history at the start: three ETDRK4 steps backward from x's y and r
  // at `phase`.
  void start_adams(AdamsState& adams, const RollingPhase& phase, const BallArrays& balls) const;
  // How far the Adams method is ahead of the last sample, s.
  double adams_lead_s(const AdamsState& adams) const {
    return adams.lead / (options_.sample_rate_hz * step_ratio_.steps);
  }
  // Linear part of the exponential integrator at displacement q: stiffness and damping of
  // the contacts there, its matrix exponential and phi functions for the internal step.
  void linearize(const Vector5& q, const RollingPhase& phase);
  bool exponential() const { return options_.method != IntegrationMethod::Rk4; }
  bool adams() const {
    return options_.method == IntegrationMethod::ExponentialAdams ||
           options_.method == IntegrationMethod::ExponentialAdamsPec;
  }
  void integrate_sample_adams(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                              const BallArrays& balls, AdamsState& adams, Vector5* a_end) const;
  // cos and sin of the cage's turn in half an internal step (cached while it stays the same).
  CageTrig half_step_rotation() const;
  double contact_margin_m(const Vector5& q, const Vector5& v, const Vector5& a) const;
  DynamicSample commit_sample(const Vector5& q, const Vector5& v, const Vector5& a, const RollingPhase& phase);
  void update_cage_speed();
  void update_substeps();
  void update_slip_fluctuation();

  BearingModel model_;
  DynamicsOptions options_;
  Matrix5 inverse_mass_ = Matrix5::Zero();  // of BearingModel::mass_matrix (full with a carried body)
  bool inverse_mass_is_diagonal_ = false;
  Vector5 inverse_mass_diagonal_ = Vector5::Zero();
  void set_inverse_mass(const Matrix5& inverse_mass);
  Vector5 divided_by_mass(const Vector5& force) const;  // M^-1 force
  double ring_speed_ = 0.0;
  double cage_speed_ = 0.0, inner_speed_ = 0.0, outer_speed_ = 0.0, spin_speed_ = 0.0;
  RollingPhase phase_;
  // Random part of the cage slip (imperfections), per sample.
  double slip_fluctuation_ = 0.0;
  std::mt19937_64 slip_rng_;
  std::normal_distribution<double> slip_noise_{0.0, 1.0};
  StepRatio step_ratio_;
  double substeps_load_norm_ = 0.0;  // |load| when the substeps were chosen
  double displacement_limit_m_ = 0.0;
  double slowest_mode_rad_s_ = 0.0;  // for the contact margin
  std::uint64_t sample_index_ = 0;
  DynamicSample current_;
  bool acceleration_current_ = false;
  // The external load in time: load + rate (t - mid_time_s) (a rate only within a sample
  // given an end load; `load` is what the step choice, the linearization and the statics
  // use), and the load that current_.acceleration holds.
  struct LoadLine {
    Vector5 load = Vector5::Zero(), rate = Vector5::Zero();
    double mid_time_s = 0.0;
    Vector5 at(double time_s) const { return load + rate * (time_s - mid_time_s); }
  };
  LoadLine load_line_;
  Vector5 load_in_current_acceleration_ = Vector5::Zero();
  // Replaces the load line, moving the current acceleration and the Adams remainders with it.
  void change_load(const LoadLine& line);
  // The balls integrated (near contact by the margin) and the others, split every
  // kSamplesPerBallSplit samples (see step()).
  struct BallSplit {
    BallArrays active, clear;
    std::uint64_t full_sample_retries = 0;  // samples redone with every ball
    int samples_since = 0;                  // 0: split again before the next sample
    // Since the last split: its displacement, the largest deflection (spalls left out) of a
    // clear ball then, and the rolling travel (|cage|, |cage - outer|, |cage - inner|, |spin|, rad).
    Vector5 displacement = Vector5::Zero();
    double clear_max_deflection_m = 0.0;
    std::array<double, 4> travel{};
  };
  BallSplit split_;
  static constexpr int kSamplesPerBallSplit = 16;
  // The integrators' state (integrator_state.hpp): the exponential integrators' linear part
  // and ETDRK4's weights, the Adams methods' weights and their running state.
  integrators::EtdState etd_;
  integrators::AdamsWeights adams_weights_;
  AdamsState adams_;
  static constexpr int kSamplesPerCageTrig = 16;
  // Upper bound of every clear ball's deflection at q after `travel` (see step()).
  double clear_deflection_bound_m(const Vector5& q, const std::array<double, 4>& travel) const;
};

}  // namespace bearing_sim
