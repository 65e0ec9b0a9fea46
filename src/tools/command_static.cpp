// bearing_tool static: quasi-static equilibrium, stiffness and ball loads (docs/model.md section 6).
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "bearing_sim/core/quasi_static.hpp"
#include "commands.hpp"
#include "flexible_ring_report.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct StaticOptions {
  double ring_temperature_difference_K = 0.0;
  std::string bearing;
  std::vector<double> force{0.0, 0.0, 0.0};
  std::vector<double> moment{0.0, 0.0};
  double cage_angle_deg = 0.0;
  bool json = false;
};

const char* const kDofNames[5] = {"x", "y", "z", "theta_x", "theta_y"};

double azimuth_deg_0_360(double azimuth_rad) {
  double deg = rad_to_deg(azimuth_rad);
  if (deg < 0.0) deg += 360.0;
  if (deg >= 360.0) deg -= 360.0;
  return deg;
}

std::string pressure_warning(const StaticSolution& sol) {
  std::ostringstream os;
  os << "maximum contact pressure " << fixed(sol.max_contact_pressure_Pa / 1e6, 0) << " MPa exceeds the permissible "
     << fixed(kPermissibleContactPressurePa / 1e6, 0) << " MPa (ISO 76): the static load is beyond the usual limit";
  return os.str();
}

nlohmann::json solution_json(const StaticOptions& o, const BearingModel& model, const Vector5& load,
                             const StaticSolution& sol) {
  nlohmann::json balls = nlohmann::json::array();
  for (const auto& b : sol.balls) {
    balls.push_back({{"row", b.row},
                     {"index", b.index_in_row},
                     {"azimuth_deg", azimuth_deg_0_360(b.azimuth_rad)},
                     {"load_N", b.load_N},
                     {"contact_angle_deg", rad_to_deg(b.contact_angle_rad)},
                     {"deflection_m", b.deflection_m},
                     {"pressure_Pa", b.pressure_Pa},
                     {"normal", {b.normal.x(), b.normal.y(), b.normal.z()}}});
  }
  nlohmann::json warnings = nlohmann::json::array();
  if (sol.exceeds_permissible_pressure()) warnings.push_back(pressure_warning(sol));
  return {{"bearing", bearing_json(model, o.bearing)},
          {"load", to_json(load)},
          {"cage_angle_deg", o.cage_angle_deg},
          {"displacement", to_json(sol.displacement)},
          {"stiffness", matrix_to_json(sol.stiffness)},
          {"bushing_matrix", matrix_to_json(bushing_matrix(sol.stiffness))},
          {"max_ball_load_N", sol.max_ball_load_N},
          {"max_contact_pressure_Pa", sol.max_contact_pressure_Pa},
          {"permissible_contact_pressure_Pa", kPermissibleContactPressurePa},
          {"iterations", sol.iterations},
          {"residual_N", sol.residual_norm},
          {"balls", balls},
          {"warnings", warnings}};
}

void print_tables(const StaticOptions& o, const BearingModel& model, const Vector5& load, const StaticSolution& sol) {
  std::ostream& out = std::cout;
  const auto& c = model.config();
  out << "Bearing: " << c.name << " (" << o.bearing << ")\n"
      << "  " << c.rows << " row(s) x " << c.balls_per_row << " balls, moving ring: " << rotating_ring_name(model)
      << "\n";
  out << "Load on the moving ring: Fx=" << general(load[0], 6) << " N, Fy=" << general(load[1], 6)
      << " N, Fz=" << general(load[2], 6) << " N, Mx=" << general(load[3], 6) << " N*m, My=" << general(load[4], 6)
      << " N*m\n\n";

  out << "Displacement and stiffness (diagonal)\n";
  Table disp({"dof", "displacement", "unit", "stiffness", "unit"}, {true, false, true, false, true});
  for (int i = 0; i < 5; ++i) {
    const bool tilt = i >= 3;
    disp.add_row({kDofNames[i], fixed(sol.displacement[i] * 1e6, 4), tilt ? "urad" : "um",
                  general(sol.stiffness(i, i) * 1e-6, 5), tilt ? "N*m/urad" : "N/um"});
  }
  disp.print(out);

  out << "\nStiffness matrix K = -dF/dq (SI: N/m, N/rad, N*m/m, N*m/rad; rows and columns x y z theta_x "
         "theta_y)\n";
  Table k({"", "x", "y", "z", "theta_x", "theta_y"}, {true});
  for (int r = 0; r < 5; ++r) {
    std::vector<std::string> row{kDofNames[r]};
    for (int col = 0; col < 5; ++col) row.push_back(scientific(sol.stiffness(r, col), 4));
    k.add_row(row);
  }
  k.print(out);

  out << "\nSummary\n";
  KeyValueList summary;
  summary.add("max ball load", fixed(sol.max_ball_load_N, 2) + " N");
  summary.add("max contact pressure", fixed(sol.max_contact_pressure_Pa / 1e6, 1) + " MPa (permissible " +
                                          fixed(kPermissibleContactPressurePa / 1e6, 0) + " MPa, ISO 76)");
  int loaded = 0;
  for (const auto& b : sol.balls) loaded += b.load_N > 0.0;
  summary.add("loaded balls", std::to_string(loaded) + " of " + std::to_string(sol.balls.size()));
  summary.add("Newton iterations",
              std::to_string(sol.iterations) + " (residual " + general(sol.residual_norm, 3) + " N)");
  summary.print(out);

  out << "\nLoaded balls\n";
  Table balls({"row", "ball", "azimuth deg", "load N", "contact angle deg", "deflection um", "pressure MPa"});
  for (const auto& b : sol.balls) {
    if (!(b.load_N > 0.0)) continue;
    balls.add_row({std::to_string(b.row + 1), std::to_string(b.index_in_row + 1),
                   fixed(azimuth_deg_0_360(b.azimuth_rad), 2), fixed(b.load_N, 2),
                   fixed(rad_to_deg(b.contact_angle_rad), 3), fixed(b.deflection_m * 1e6, 4),
                   fixed(b.pressure_Pa / 1e6, 1)});
  }
  balls.print(out);
}

void run(const StaticOptions& o) {
  const BearingModel model = load_model(o.bearing, o.ring_temperature_difference_K);
  const Vector5 load = make_load(o.force, o.moment);
  const RollingPhase phase{deg_to_rad(o.cage_angle_deg)};
  StaticSolution sol = solve_static(model, load, phase);
  nlohmann::json ring = nullptr;  // with a flexible ring: its shape and modes, and the rigid ring's peak
  if (model.config().flexible_ring.present) {
    const FlexibleBearing flexible(model);
    const FlexibleStaticSolution flexible_solution = solve_flexible_static(flexible, load, phase);
    ring = flexible_ring_static_json(flexible, flexible_solution, sol);
    sol = flexible_solution.rigid_coordinates;
  }
  nlohmann::json result = solution_json(o, model, load, sol);
  result["flexible_ring"] = ring;
  require_finite_result(result, "static");
  if (sol.exceeds_permissible_pressure()) warn(pressure_warning(sol));
  if (o.json) {
    print_json(result);
    return;
  }
  print_tables(o, model, load, sol);
  if (!ring.is_null()) print_flexible_ring_static(ring);
}

}  // namespace

void register_static_command(CLI::App& app) {
  auto o = std::make_shared<StaticOptions>();
  CLI::App* cmd =
      app.add_subcommand("static",
                         "Quasi-static equilibrium of the moving ring under a load: displacement, 5x5 stiffness "
                         "(and the 6x6 Bushing matrix), ball loads, contact angles and Hertz pressures");
  add_bearing_option(cmd, &o->bearing);
  add_load_options(cmd, &o->force, &o->moment);
  add_ring_temperature_option(cmd, &o->ring_temperature_difference_K,
                              "Inner minus outer ring temperature, K: changes the clearance (docs/model.md 3.7)");
  add_number_option(cmd, "--cage-angle-deg", &o->cage_angle_deg, "DEG",
                    "Cage angle: azimuth of the first ball of row 1, deg");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
