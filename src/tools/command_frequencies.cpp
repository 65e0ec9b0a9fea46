// bearing_tool frequencies: cage, ball-pass and ball-spin frequencies (docs/model.md section 8.1).
#include <cmath>
#include <iostream>
#include <memory>

#include "bearing_sim/core/frequencies.hpp"
#include "commands.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct FrequenciesOptions {
  std::string bearing;
  double outer_rpm = 0.0;
  double inner_rpm = 0.0;
  bool json = false;
};

void run(const FrequenciesOptions& o) {
  const BearingModel model = load_model(o.bearing);
  const BearingFrequencies f = bearing_frequencies(model, rpm_to_rad_s(o.inner_rpm), rpm_to_rad_s(o.outer_rpm));
  const nlohmann::json result = {{"bearing", bearing_json(model, o.bearing)},
                                 {"inner_rpm", o.inner_rpm},
                                 {"outer_rpm", o.outer_rpm},
                                 {"cage_hz", f.cage_hz},
                                 {"ball_pass_outer_race_hz", f.ball_pass_outer_race_hz},
                                 {"ball_pass_inner_race_hz", f.ball_pass_inner_race_hz},
                                 {"ball_spin_hz", f.ball_spin_hz},
                                 {"relative_ring_hz", f.relative_ring_hz},
                                 {"varying_compliance_hz", f.varying_compliance_hz}};
  require_finite_result(result, "frequencies");
  if (o.json) {
    print_json(result);
    return;
  }
  std::ostream& out = std::cout;
  out << "Bearing: " << model.config().name << " (" << o.bearing << ")\n"
      << "Speeds: inner ring " << general(o.inner_rpm, 6) << " rpm, outer ring " << general(o.outer_rpm, 6)
      << " rpm\n\n";
  const double fr = f.relative_ring_hz;
  Table t({"frequency", "Hz", "x relative ring speed"}, {true});
  auto row = [&](const char* name, double hz) { t.add_row({name, fixed(hz, 4), fr > 0.0 ? fixed(hz / fr, 5) : "-"}); };
  row("relative ring speed f_r", f.relative_ring_hz);
  row("cage (FTF)", f.cage_hz);
  row("ball pass, outer race (BPFO)", f.ball_pass_outer_race_hz);
  row("ball pass, inner race (BPFI)", f.ball_pass_inner_race_hz);
  row("ball spin (BSF)", f.ball_spin_hz);
  row("varying compliance Z*f_c", f.varying_compliance_hz);
  t.print(out);
}

}  // namespace

void register_frequencies_command(CLI::App& app) {
  auto o = std::make_shared<FrequenciesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "frequencies", "Cage, ball-pass (outer and inner race), ball-spin and varying-compliance frequencies");
  add_bearing_option(cmd, &o->bearing);
  add_number_option(cmd, "--outer-rpm", &o->outer_rpm, "RPM", "Outer ring speed, rpm (signed)");
  add_number_option(cmd, "--inner-rpm", &o->inner_rpm, "RPM", "Inner ring speed, rpm (signed)");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
