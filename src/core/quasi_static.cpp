#include "bearing_sim/core/quasi_static.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace {

// Angles are scaled by the pitch radius and moments divided by it, so that every
// coordinate is a length and every residual a force.
Vector5 scales(const BearingModel& model) {
  Vector5 s;
  s << 1, 1, 1, model.pitch_radius_m(), model.pitch_radius_m();
  return s;
}

std::string describe(const Vector5& load) {
  std::ostringstream os;
  os << "Fx=" << load[0] << " N, Fy=" << load[1] << " N, Fz=" << load[2] << " N, Mx=" << load[3]
     << " N*m, My=" << load[4] << " N*m";
  return os.str();
}

}  // namespace

StaticSolution solve_static(const BearingModel& model, const Vector5& load, const RollingPhase& phase,
                            const StaticSolverOptions& options, const Vector5* initial_guess) {
  if (!load.allFinite()) throw InvalidInputError("static load is not finite: " + describe(load));
  if (!std::isfinite(phase.cage)) throw InvalidInputError("cage angle is not finite");
  if (std::abs(phase.cage) > kMaxAngleRad) {
    std::ostringstream why;
    why << "cage angle " << phase.cage << " rad is beyond +-" << kMaxAngleRad
        << " rad (the balls' places are lost in its rounding; give it within a turn)";
    throw InvalidInputError(why.str());
  }

  const Vector5 s = scales(model);
  const double d = model.config().ball_diameter_m;
  // Beyond this the balls would have left the grooves: the load is not carried.
  const double displacement_limit = 0.25 * d + std::abs(model.clearance_m());
  const double load_scale = (load.array() / s.array()).matrix().norm();
  // Finite components whose magnitude overflows (1e300 N) would turn every step into NaN.
  if (!std::isfinite(load_scale))
    throw InvalidInputError("static load is beyond any bearing (its magnitude overflows): " + describe(load));
  const double tolerance = options.force_tolerance_N + 1e-12 * load_scale;

  // Start where a single ball stiffness scaled by the ball count would put the ring;
  // it only needs to put some balls in contact.
  Vector5 q = Vector5::Zero();
  if (initial_guess) {
    q = *initial_guess;
  } else if (load_scale > 0.0) {
    const double per_ball = load_scale / (0.2 * model.ball_count());
    const double deflection = std::cbrt(std::pow(per_ball / model.contact_stiffness(), 2.0));
    const Vector5 direction = (load.array() / s.array()).matrix() / load_scale;
    q = ((deflection + std::max(0.0, model.clearance_m())) * direction).cwiseQuotient(s);
  }

  Matrix5 k;
  auto residual = [&](const Vector5& qq, Matrix5* kk) {
    return Vector5(load + model.contact_force_and_stiffness(qq, phase, kk));
  };
  auto scaled_norm = [&](const Vector5& r) { return (r.array() / s.array()).matrix().norm(); };

  Vector5 r = residual(q, &k);
  double r_norm = scaled_norm(r);
  double mu = 0.0;  // Levenberg-Marquardt shift, used only when Newton does not descend
  int it = 0;
  for (; it < options.max_iterations && r_norm > tolerance; ++it) {
    // Scaled system: (S^-1 K S^-1 + mu I) (S dq) = S^-1 r
    const Matrix5 ks = s.asDiagonal().inverse() * k * s.asDiagonal().inverse();
    const Vector5 rs = (r.array() / s.array()).matrix();
    const double k_scale = std::max(ks.diagonal().maxCoeff(), 1.0);
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      const Matrix5 a = ks + mu * k_scale * Matrix5::Identity();
      Eigen::LDLT<Matrix5> ldlt(a);
      Vector5 step =
          (ldlt.info() == Eigen::Success && ldlt.isPositive()) ? Vector5(ldlt.solve(rs)) : Vector5(rs / k_scale);
      if (!step.allFinite()) step = rs / k_scale;
      // Never move more than a tenth of a ball diameter in one iteration.
      const double step_norm = step.norm();
      if (step_norm > 0.1 * d) step *= 0.1 * d / step_norm;
      const Vector5 q_try = q + step.cwiseQuotient(s);
      Matrix5 k_try;
      const Vector5 r_try = residual(q_try, &k_try);
      const double n_try = scaled_norm(r_try);
      if (std::isfinite(n_try) && n_try < r_norm) {
        q = q_try;
        r = r_try;
        k = k_try;
        r_norm = n_try;
        mu = mu > 0.0 ? mu * 0.1 : 0.0;
        if (mu < 1e-12) mu = 0.0;
        accepted = true;
      } else {
        mu = mu > 0.0 ? mu * 10.0 : 1e-6;
      }
    }
    const double translation = q.head<3>().norm();
    const double tilt = q.tail<2>().norm() * model.pitch_radius_m();
    if (!accepted || translation > displacement_limit || tilt > displacement_limit) {
      std::ostringstream os;
      os << "the bearing '" << model.config().name << "' cannot carry the load " << describe(load)
         << ": no equilibrium (ring displacement " << translation * 1e6 << " um, tilt at the pitch radius "
         << tilt * 1e6 << " um, unbalanced force " << r_norm << " N after " << it + 1 << " iterations)";
      throw LoadNotCarriedError(os.str());
    }
  }
  if (r_norm > tolerance) {
    std::ostringstream os;
    os << "the bearing '" << model.config().name << "' cannot carry the load " << describe(load)
       << ": Newton did not converge in " << options.max_iterations << " iterations (unbalanced force " << r_norm
       << " N)";
    throw LoadNotCarriedError(os.str());
  }

  StaticSolution sol;
  sol.displacement = q;
  model.contact_force_and_stiffness(q, phase, &sol.stiffness);
  sol.balls = model.ball_states(q, phase);
  for (const auto& b : sol.balls) {
    sol.max_ball_load_N = std::max(sol.max_ball_load_N, b.load_N);
    sol.max_contact_pressure_Pa = std::max(sol.max_contact_pressure_Pa, b.pressure_Pa);
  }
  sol.residual_norm = r_norm;
  sol.iterations = it;
  return sol;
}

}  // namespace bearing_sim
