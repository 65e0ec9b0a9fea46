// bearing_tool modes: natural frequencies and mode shapes of a rigid body on one or more
// identical bearings, each a 6x6 Bushing spring from the quasi-static stiffness at the
// given load (core/modal_analysis.hpp); --no-angular-stiffness drops the bearings'
// rotational stiffness (the INS paper's comparison, its table 2; docs/model.md section 6.5).
#include <cmath>
#include <iostream>
#include <memory>

#include "bearing_sim/core/flexible_bearing.hpp"
#include "bearing_sim/core/modal_analysis.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "commands.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct ModesOptions {
  std::string bearing;
  std::vector<double> force{0.0, 0.0, 0.0};
  std::vector<double> moment{0.0, 0.0};
  double mass_kg = 0.0;
  std::vector<double> inertia{0.0, 0.0, 0.0};
  std::vector<double> positions_mm{0.0};
  bool no_angular = false;
  bool json = false;
};

void run(const ModesOptions& o) {
  // The core's limits (solve_modes refuses the same), named here as the user gave them.
  if (!(o.mass_kg >= kMinBodyMassKg && o.mass_kg <= kMaxBodyMassKg))
    throw InputError("--mass-kg " + general(o.mass_kg, 6) + ": must be from " + general(kMinBodyMassKg, 3) + " to " +
                     general(kMaxBodyMassKg, 3) + " kg");
  for (double i : o.inertia)
    if (!(i >= kMinBodyInertiaKgM2 && i <= kMaxBodyInertiaKgM2))
      throw InputError("--inertia-kg-m2 " + general(i, 6) + ": every component must be from " +
                       general(kMinBodyInertiaKgM2, 3) + " to " + general(kMaxBodyInertiaKgM2, 3) + " kg*m^2");
  for (double z_mm : o.positions_mm)
    if (!(std::abs(z_mm) * 1e-3 <= kMaxSupportDistanceM))
      throw InputError("--bearing-positions-mm " + general(z_mm, 6) + ": a bearing must be within +-" +
                       general(kMaxSupportDistanceM * 1e3, 6) + " mm of the centre of mass");
  const BearingModel model = load_model(o.bearing);
  const Vector5 load = make_load(o.force, o.moment);
  // A flexible ring's bushing: its stiffness with the ring's modes statically condensed out.
  const StaticSolution sol = model.config().flexible_ring.present
                                 ? solve_flexible_static(FlexibleBearing(model), load).rigid_coordinates
                                 : solve_static(model, load);
  const Matrix6 bushing = bushing_matrix(sol.stiffness);
  if (bushing(0, 0) <= 0.0 || bushing(2, 2) <= 0.0)
    warn(
        "the bearing has no radial or axial stiffness at this load (zero load on a bearing with clearance?): "
        "give a load or a preload");

  RigidBody body;
  body.mass_kg = o.mass_kg;
  body.inertia_kg_m2 << o.inertia[0], o.inertia[1], o.inertia[2];
  std::vector<BushingSupport> supports;
  for (double z_mm : o.positions_mm) supports.push_back({bushing, Eigen::Vector3d(0.0, 0.0, z_mm * 1e-3)});
  ModalOptions options;
  options.zero_angular_stiffness = o.no_angular;
  const ModalResult res = solve_modes(body, supports, options);

  nlohmann::json modes = nlohmann::json::array();
  for (std::size_t i = 0; i < res.modes.size(); ++i) {
    const Mode& m = res.modes[i];
    nlohmann::json shape = nlohmann::json::array(), energy = nlohmann::json::array();
    for (int k = 0; k < 6; ++k) {
      shape.push_back(m.shape[k]);
      energy.push_back(m.energy_fraction[k]);
    }
    modes.push_back({{"order", i + 1},
                     {"frequency_hz", m.frequency_hz},
                     {"free", m.free},
                     {"dominant_dof", rigid_dof_name(m.dominant_dof)},
                     {"shape", shape},
                     {"energy_fraction", energy}});
  }
  const nlohmann::json result = {{"bearing", bearing_json(model, o.bearing)},
                                 {"load_per_bearing", to_json(load)},
                                 {"bearing_positions_mm", o.positions_mm},
                                 {"angular_stiffness", !o.no_angular},
                                 {"mass_kg", o.mass_kg},
                                 {"inertia_kg_m2", o.inertia},
                                 {"bushing_matrix", matrix_to_json(bushing)},
                                 {"Kr_N_per_m", bushing(0, 0)},
                                 {"Ka_N_per_m", bushing(2, 2)},
                                 {"Ktheta_Nm_per_rad", bushing(4, 4)},
                                 {"stiffness_at_centre_of_mass", matrix_to_json(res.stiffness)},
                                 {"mass_matrix", matrix_to_json(res.mass)},
                                 {"modes", modes}};
  require_finite_result(result, "modes");
  if (o.json) {
    print_json(result);
    return;
  }
  std::ostream& out = std::cout;
  out << "Bearing: " << model.config().name << " (" << o.bearing << "), " << o.positions_mm.size() << " at z =";
  for (double z : o.positions_mm) out << ' ' << general(z, 5);
  out << " mm from the centre of mass\n";
  KeyValueList k;
  k.add("Kr (K_xx)", general(bushing(0, 0) * 1e-6, 5) + " N/um");
  k.add("Ka (K_zz)", general(bushing(2, 2) * 1e-6, 5) + " N/um");
  k.add("Ktheta (K_theta_y)",
        general(bushing(4, 4), 5) + " N*m/rad" + (o.no_angular ? " (zeroed: --no-angular-stiffness)" : ""));
  k.add("body", general(o.mass_kg, 5) + " kg, I = " + general(o.inertia[0], 4) + ", " + general(o.inertia[1], 4) +
                    ", " + general(o.inertia[2], 4) + " kg*m^2");
  k.print(out);
  out << "\nModes (kinetic energy share per coordinate, %)\n";
  Table t({"mode", "f Hz", "dominant", "x", "y", "z", "rx", "ry", "rz"}, {false, false, true});
  for (std::size_t i = 0; i < res.modes.size(); ++i) {
    const Mode& m = res.modes[i];
    std::vector<std::string> row{std::to_string(i + 1), m.free ? "free" : fixed(m.frequency_hz, 1),
                                 rigid_dof_name(m.dominant_dof)};
    for (int c = 0; c < 6; ++c) row.push_back(fixed(100.0 * m.energy_fraction[c], 1));
    t.add_row(row);
  }
  t.print(out);
}

}  // namespace

void register_modes_command(CLI::App& app) {
  auto o = std::make_shared<ModesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "modes",
      "Natural frequencies and mode shapes of a rigid body on identical bearings (6x6 Bushing springs from "
      "the quasi-static stiffness at the given load per bearing), with or without their angular stiffness");
  add_bearing_option(cmd, &o->bearing);
  add_vector_option(cmd, "--force", &o->force, {"FX", "FY", "FZ"},
                    "Force on the moving ring of each bearing (sets the linearisation point), N");
  add_vector_option(cmd, "--moment", &o->moment, {"MX", "MY"}, "Moment on the moving ring of each bearing, N*m");
  add_number_option(cmd, "--mass-kg", &o->mass_kg, "KG", "Mass of the rigid body, kg")->required();
  add_vector_option(cmd, "--inertia-kg-m2", &o->inertia, {"IXX", "IYY", "IZZ"},
                    "Principal moments of inertia about the centre of mass, kg*m^2 (z: bearing axis)")
      ->required();
  cmd->add_option("--bearing-positions-mm", o->positions_mm,
                  "Axial positions of the bearings relative to the centre of mass, mm (one bearing per value) "
                  "[default: 0]")
      ->delimiter(',')
      ->expected(1, 16)
      ->type_name("Z1[,Z2...]")
      ->check(finite_number());
  cmd->add_flag("--no-angular-stiffness", o->no_angular,
                "Zero the bearings' rotational stiffness (translational springs only)");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
