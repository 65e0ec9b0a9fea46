// bearing_tool sweep: parameter studies from a YAML definition (core/sweep.hpp), run in
// parallel, one CSV row per case.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/sweep.hpp"
#include "commands.hpp"
#include "job_size.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct SweepOptions {
  std::string definition;
  std::string csv;
  int threads = 0;
  bool json = false;
  bool quiet = false;
};

nlohmann::json result_json(const SweepResult& r) {
  nlohmann::json j = {{"study", r.c.study + 1},
                      {"parameter", r.c.parameter},
                      {"value", r.c.value},
                      {"imperfection_set", r.c.imperfection_set_name},
                      {"ok", r.ok},
                      {"load", to_json(r.c.operating_point.load)},
                      {"wall_s", r.wall_s}};
  if (!r.ok) {
    j["error"] = r.error;
    return j;
  }
  j["displacement"] = to_json(r.statics.displacement);
  j["stiffness"] = matrix_to_json(r.statics.stiffness);
  j["max_ball_load_N"] = r.statics.max_ball_load_N;
  j["max_contact_pressure_Pa"] = r.statics.max_contact_pressure_Pa;
  if (r.dynamic) {
    j["a_rms_x"] = r.dynamics.a_rms_x;
    j["a_rms_y"] = r.dynamics.a_rms_y;
    j["a_rms_z"] = r.dynamics.a_rms_z;
    j["L_dB"] = r.dynamics.level_db;
    j["substeps"] = r.dynamics.substeps;
  }
  return j;
}

// A dynamic case whose bearing values give the ring a mode no bearing has would stall the
// integrator for days: the sweep is refused before any case runs, naming the case and the key
// (as simulate and generate do). A case that fails otherwise fails when run, with its reason.
void check_every_case_integrator_work(const SweepDefinition& def, const std::vector<SweepCase>& cases) {
  if (!def.dynamic) return;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SweepCase& c = cases[i];
    std::optional<BearingModel> model;
    try {
      model.emplace(c.config);
    } catch (const std::exception&) {
      continue;
    }
    const std::string where = "sweep definition " + def.source + ", case " + std::to_string(i + 1) + " (" +
                              c.parameter + " = " + general(c.value, 6) + ", imperfections " + c.imperfection_set_name +
                              "), bearing " + def.bearing_path;
    try {
      check_integrator_work(*model, c.operating_point.load, c.operating_point.sample_rate_hz, where);
    } catch (const ConfigError&) {
      throw;
    } catch (const std::exception&) {  // no equilibrium: the case fails when run
    }
  }
}

void run(const SweepOptions& o) {
  const SweepDefinition def = load_sweep_definition(o.definition);
  const std::vector<SweepCase> cases = sweep_cases(def);
  check_every_case_integrator_work(def, cases);
  const std::size_t total = cases.size();
  std::ofstream csv(o.csv);
  if (!csv) throw InputError("--csv: cannot open '" + o.csv + "' for writing: " + std::strerror(errno));
  if (!o.quiet)
    std::cerr << "bearing_tool sweep: " << def.name << ": " << total << " cases ("
              << (def.dynamic ? "dynamic" : "static") << ")\n";
  auto results = run_sweep(def, o.threads, [&](const SweepResult& r, std::size_t done, std::size_t n) {
    if (o.quiet) return;
    std::cerr << "  [" << done << "/" << n << "] " << r.c.parameter << " = " << general(r.c.value, 6) << " ("
              << r.c.imperfection_set_name << "): "
              << (r.ok ? (r.dynamic ? "L " + fixed(r.dynamics.level_db, 2) + " dB" : std::string("ok"))
                       : "error: " + r.error)
              << '\n';
  });
  // A case whose result is not finite fails like any other (no NaN in the CSV or the table).
  for (auto& r : results) {
    if (!r.ok) continue;
    try {
      require_finite_result(result_json(r), "sweep case", {"L_dB"});
    } catch (const NonFiniteResultError& e) {
      r.ok = false;
      r.error = e.what();
    }
  }
  csv << sweep_csv_header() << '\n';
  for (const auto& r : results) csv << sweep_csv_row(r) << '\n';
  csv.close();
  if (!csv) throw std::runtime_error("--csv: error writing '" + o.csv + "'");

  int failed = 0;
  for (const auto& r : results) failed += !r.ok;
  if (failed > 0)
    warn(std::to_string(failed) + " of " + std::to_string(results.size()) +
         " cases failed (status 'error' in the CSV, with the reason)");
  if (o.json) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& r : results) rows.push_back(result_json(r));
    print_json({{"name", def.name},
                {"definition", o.definition},
                {"bearing", def.bearing_path},
                {"analysis", def.dynamic ? "dynamic" : "static"},
                {"csv", o.csv},
                {"cases", results.size()},
                {"failed", failed},
                {"results", rows}});
    return;
  }
  Table t({"study", "parameter", "value", "imperfections", "Kxx N/um", "Kzz N/um", "Kty N*m/urad", "L dB"},
          {false, true, false, true});
  for (const auto& r : results) {
    t.add_row({std::to_string(r.c.study + 1), r.c.parameter, general(r.c.value, 6), r.c.imperfection_set_name,
               r.ok ? general(r.statics.stiffness(0, 0) * 1e-6, 5) : "error",
               r.ok ? general(r.statics.stiffness(2, 2) * 1e-6, 5) : "",
               r.ok ? general(r.statics.stiffness(4, 4) * 1e-6, 5) : "",
               r.ok && r.dynamic ? fixed(r.dynamics.level_db, 2) : ""});
  }
  std::cout << "Sweep: " << def.name << " (" << o.definition << "), bearing " << def.bearing_path << "\n";
  t.print(std::cout);
  std::cout << "CSV: " << o.csv << "\n";
}

}  // namespace

void register_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  std::string params;
  for (const auto& p : sweep_parameters()) params += "\n  " + p.name + ": " + p.description;
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Parameter studies from a YAML definition (base bearing file, operating point, imperfection sets, "
      "studies): quasi-static stiffness and, for dynamic sweeps, a_rms and L per case, in parallel, CSV out");
  cmd->footer("Parameters a study may vary:" + params);
  cmd->add_option("--definition", o->definition, "Sweep definition (YAML, docs/bearing_tool.md)")
      ->required()
      ->type_name("FILE");
  cmd->add_option("--csv", o->csv, "Output CSV, one row per case")->required()->type_name("FILE");
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores) [default: 0]")
      ->type_name("N")
      ->check(CLI::Range(0, 256));
  cmd->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
