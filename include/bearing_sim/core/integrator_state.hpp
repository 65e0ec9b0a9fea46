#pragma once
// The state of BearingDynamics' exponential integrators (bearing_dynamics.hpp), one type per
// integrator: what ETDRK4 and the Adams methods share (the linearized contacts, ETDRK4's
// weights), the Adams methods' weights and their running state. Classical RK4 keeps none.
// Internal to BearingDynamics; public only because its members need the complete types.
#include <array>
#include <cstdint>
#include <limits>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::integrators {

using Vector10 = Eigen::Matrix<double, 10, 1>;
using Matrix10 = Eigen::Matrix<double, 10, 10>;
using Matrix10x5 = Eigen::Matrix<double, 10, 5>;

// cos and sin of a cage angle, carried along with it by the exponential integrators.
struct CageTrig {
  double c = 1.0, s = 0.0;
};

// Samples per step the Adams methods may fall between (BearingDynamics::choose_step_ratio).
constexpr int kAdamsStepSampleDivisions = 4;

// The exponential integrators' linear part: y = (q - q_lin, v), y' = L y + (0, r), L = [0 I; A],
// the remainder r = a(q, v, t) - A y. Stored for ETDRK4: e^{hL}, e^{hL/2}, the phi-function
// blocks that multiply the remainder, for the internal step h (for -h with the Adams
// methods, whose history they make backward in time).
struct EtdState {
  Vector5 q_lin = Vector5::Zero();
  Vector5 load_lin = Vector5::Zero();
  Eigen::Matrix<double, 5, 10> lin_accel = Eigen::Matrix<double, 5, 10>::Zero();  // A
  Matrix10 exp_full = Matrix10::Identity(), exp_half = Matrix10::Identity();
  Matrix10x5 phi_half = Matrix10x5::Zero();  // (h/2) phi1(hL/2)
  Matrix10x5 w1 = Matrix10x5::Zero(), w2 = Matrix10x5::Zero(), w3 = Matrix10x5::Zero();
  double step_s = 0.0;  // the internal step linearized for; 0: again before the next sample
  int samples_since_linearization = 0;
  std::uint64_t linearizations = 0;
  // The cage turn of half an internal step and its cos and sin (recomputed when it changes),
  // and cos and sin of the cage angle at the end of the last sample ETDRK4 integrated.
  mutable double half_step_turn = std::numeric_limits<double>::quiet_NaN();
  mutable CageTrig half_step_rotation;
  mutable CageTrig sample_end_trig;
};

// The Adams methods' weights, for the linearization of EtdState.
struct AdamsWeights {
  // The predictor [E P] (e^{hL} and the weights P of the remainder at the step's start and of
  // the history entries, side by side) over its linear part A [E P], one 15x30 product with
  // (y, r, r_-1, r_-2, r_-3) giving y_p and A y_p. The corrector is the predicted end plus the
  // weight of the predicted end's remainder times the fourth backward difference of the
  // remainders (the two cubics differ by exactly that term), one 10x5 product.
  Eigen::Matrix<double, 15, 30> step = Eigen::Matrix<double, 15, 30>::Zero();
  Matrix10x5 corrector = Matrix10x5::Zero();
  // A sample at theta of the last step (0 < theta < 1; entry lead - 1 for theta = 1 - lead /
  // samples of the step ratio): (y, A y + r)(theta) = D (y_last_start, r_end, r, r_-1, r_-2)
  // from the corrector's cubic through the four remainders, exact in the linear part.
  std::array<Eigen::Matrix<double, 15, 30>, kAdamsStepSampleDivisions - 1> sample_within_step{};
};

// The Adams method's own state, which runs ahead of the output samples by less than one
// internal step: x = (y, r, r_-1, r_-2, r_-3) at its time, y = (q - q_lin, v), r the
// remainder there and at the three step ends before (relative to the current
// linearization; the step multiplies them with its weights in one product), y at the
// start of the last step (the samples within it come from it) and how far it is ahead of
// the last sample, in 1/steps of a sample (the step ratio). Its rolling phase is the
// sample's advanced by the lead, so that the samples' phases do not depend on the step.
struct AdamsState {
  Eigen::Matrix<double, 30, 1> x = Eigen::Matrix<double, 30, 1>::Zero();
  Vector10 y_last_start = Vector10::Zero();
  int lead = 0;
  bool started = false;  // else it starts from the next sample's start
  // cos and sin of the cage angle at its time, carried by the steps' rotations into the
  // next sample (one sincos per kSamplesPerCageTrig samples: each rotation adds ~1 ulp).
  CageTrig trig{1.0, 0.0};
  double trig_cage = 0.0;
  int trig_samples = 0;  // samples it may still be carried
};

}  // namespace bearing_sim::integrators
