// bearing_tool generate: synthetic datasets from scenario files (docs/datasets.md). Each
// scenario runs in its own thread of a pool, faster than real time and without a ROS
// master, into a rosbag (the live node's topics) and/or NPY/CSV with a JSON sidecar.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/scenario_simulation.hpp"
#include "commands.hpp"
#include "dataset_bag_writer.hpp"
#include "dataset_files.hpp"
#include "dataset_plain_writer.hpp"
#include "finite_data_guard.hpp"
#include "job_size.hpp"
#include "output_size.hpp"
#include "output_space.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct GenerateOptions {
  std::vector<std::string> scenarios;
  std::string out_dir;
  std::vector<std::string> formats{"bag"};
  long long seed = -1;      // -1: each scenario's own
  double duration_s = 0.0;  // 0: each scenario's own
  double ring_temperature_difference_K = 0.0;
  bool ring_temperature_given = false;  // else each scenario's time line
  unsigned threads = 0;                 // 0: hardware concurrency
  double label_rate_hz = 10.0;
  double ball_loads_rate_hz = 10.0;
  double health_rate_hz = 1.0;
  bool quiet = false;
  bool allow_long_run = false;
};

struct Job {
  std::string file;
  std::unique_ptr<runtime::ScenarioSimulation> simulation;
  std::vector<std::string> outputs;
  runtime::RunStats stats;
  double wall_s = 0.0;
  std::string error;
};

// Output files are named after the scenario: letters, digits, '.', '-' and '_' kept.
std::string file_stem(const std::string& scenario_name) {
  std::string stem = scenario_name;
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return stem;
}

// A job's files in --out: <out>/<stem> and what each format adds to it (dataset_files.hpp).
std::string output_stem(const GenerateOptions& o, const Job& job) {
  return o.out_dir + "/" + file_stem(job.simulation->info().scenario);
}
std::vector<std::string> output_files(const GenerateOptions& o, const Job& job) {
  std::vector<std::string> files;
  for (const std::string& f : o.formats)
    for (const std::string& file : dataset_files(output_stem(o, job), f)) files.push_back(file);
  return files;
}

void prepare_out_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out: cannot create directory '" + dir + "': " + ec.message());
  if (!fs::is_directory(dir)) throw InputError("--out: '" + dir + "' is not a directory");
  if (::access(dir.c_str(), W_OK) != 0) throw InputError("--out: directory '" + dir + "' is not writable");
}

void run_job(Job& job, const GenerateOptions& o, std::mutex& print_mutex) {
  const std::string stem = output_stem(o, job);
  std::vector<std::unique_ptr<runtime::DatasetSink>> sinks;
  sinks.push_back(std::make_unique<FiniteDataGuard>(job.simulation->info().scenario));  // before any writer
  for (const std::string& f : o.formats) {
    if (f == "bag") {
      sinks.push_back(std::make_unique<DatasetBagWriter>(dataset_files(stem, f).front()));
    } else {
      const auto format = f == "npy" ? DatasetPlainWriter::Format::Npy : DatasetPlainWriter::Format::Csv;
      sinks.push_back(std::make_unique<DatasetPlainWriter>(stem, format));
    }
  }
  job.outputs = output_files(o, job);
  std::vector<runtime::DatasetSink*> raw;
  for (auto& s : sinks) raw.push_back(s.get());
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point last_report = start;
  const double duration = job.simulation->info().duration_s;
  auto progress = [&](double simulated_s) {
    if (o.quiet) return;
    const Clock::time_point now = Clock::now();
    if (now - last_report < std::chrono::seconds(5)) return;
    last_report = now;
    const double wall = std::chrono::duration<double>(now - start).count();
    std::lock_guard<std::mutex> lock(print_mutex);
    std::fprintf(stderr, "generate: %s: %5.1f%% (%.1f of %.1f s simulated, %.1fx real time)\n",
                 job.simulation->info().scenario.c_str(), 100.0 * simulated_s / duration, simulated_s, duration,
                 simulated_s / wall);
  };
  try {
    job.stats = job.simulation->run(raw, progress);
  } catch (const std::exception& e) {
    job.error = e.what();
  }
  job.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
}

void run(const GenerateOptions& o) {
  for (const std::string& f : o.formats)
    if (f != "bag" && f != "npy" && f != "csv") throw InputError("--format: '" + f + "' is not bag, npy or csv");
  runtime::GenerateSettings settings;
  if (o.seed >= 0) settings.seed = static_cast<std::uint64_t>(o.seed);
  if (o.duration_s > 0.0) settings.duration_s = o.duration_s;
  if (o.ring_temperature_given) settings.ring_temperature_difference_K = o.ring_temperature_difference_K;
  settings.label_rate_hz = o.label_rate_hz;
  settings.ball_loads_rate_hz = o.ball_loads_rate_hz;
  settings.health_rate_hz = o.health_rate_hz;

  // Everything checked before anything runs.
  std::vector<Job> jobs(o.scenarios.size());
  std::set<std::string> names;
  for (std::size_t i = 0; i < o.scenarios.size(); ++i) {
    jobs[i].file = o.scenarios[i];
    try {
      jobs[i].simulation =
          std::make_unique<runtime::ScenarioSimulation>(Scenario::load(o.scenarios[i]), o.scenarios[i], settings);
    } catch (const ConfigError& e) {
      throw InputError(std::string("bad scenario: ") + e.what());
    } catch (const InvalidInputError& e) {
      throw InputError("scenario " + o.scenarios[i] + ": " + e.what());
    }
    if (!names.insert(file_stem(jobs[i].simulation->info().scenario)).second)
      throw InputError("two scenarios are named '" + jobs[i].simulation->info().scenario +
                       "' (or alike): their files would overwrite each other in --out");
  }
  const unsigned threads = std::max(1u, std::min<unsigned>(o.threads ? o.threads : std::thread::hardware_concurrency(),
                                                           static_cast<unsigned>(jobs.size())));
  // The integrator's work and the wall time, before anything runs.
  double total_samples = 0.0, total_estimate_s = 0.0;
  for (const Job& job : jobs) {
    const Scenario& sc = job.simulation->scenario();
    const runtime::DatasetInfo& info = job.simulation->info();
    const BearingModel model(load_bearing_config(sc.bearing_file()));
    const double samples = static_cast<double>(info.ideal_samples);
    total_samples += samples;
    try {
      for (double t : {0.0, 0.5 * info.duration_s, info.duration_s})
        check_integrator_work(model, sc.load_at(t), info.sample_rate_hz, sc.bearing_file());
      if (samples > 1000.0) {
        const double t = 0.5 * info.duration_s;
        total_estimate_s +=
            samples * measure_seconds_per_sample(model, sc.load_at(t), sc.ring_speed_at(t), info.sample_rate_hz, 0);
      }
    } catch (const ConfigError& e) {
      throw InputError("scenario " + job.file + ": " + e.what());
    } catch (const LoadNotCarriedError&) {
      // No equilibrium there: the run itself handles it as it always has; no estimate from it.
    }
  }
  check_job_size(total_samples, total_estimate_s / threads, o.allow_long_run,
                 "generate (" + std::to_string(jobs.size()) + " scenario(s) on " + std::to_string(threads) +
                     " thread(s), dynamics alone)",
                 "--allow-long-run");
  // The files' size against the free space (after the wall time, before --out is created).
  std::vector<PlannedOutput> outputs;
  for (const Job& job : jobs) {
    const BearingConfig bearing = load_bearing_config(job.simulation->scenario().bearing_file());
    // A run into an --out that holds a former run's files replaces them: their space comes back.
    outputs.push_back({"--out '" + o.out_dir + "'", output_stem(o, job),
                       dataset_output_bytes(job.simulation->info(), settings, job.simulation->scenario(),
                                            bearing.rows * bearing.balls_per_row, o.formats),
                       output_files(o, job)});
  }
  check_output_space(outputs);
  prepare_out_dir(o.out_dir);
  std::mutex print_mutex;
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < jobs.size(); i = next++) run_job(jobs[i], o, print_mutex);
    });
  for (std::thread& t : pool) t.join();

  std::size_t failed = 0;
  double simulated = 0.0, cpu = 0.0, sink_cpu = 0.0, health_cpu = 0.0;
  std::cout << "scenario                         seed  simulated s  samples (measured)  RT factor per core  "
               "output  health\n";
  for (const Job& j : jobs) {
    const runtime::DatasetInfo& info = j.simulation->info();
    if (!j.error.empty()) {
      ++failed;
      std::cerr << "bearing_tool: generate: scenario '" << info.scenario << "' (" << j.file << ") failed: " << j.error
                << '\n';
      continue;
    }
    char line[256];
    std::snprintf(line, sizeof line, "%-32s %4llu %12.2f %19llu %18.1fx %6.1f%% %6.1f%%\n", info.scenario.c_str(),
                  static_cast<unsigned long long>(info.seed), j.stats.simulated_s,
                  static_cast<unsigned long long>(j.stats.measured_samples), j.stats.realtime_factor_per_core(),
                  100.0 * j.stats.sink_cpu_s / j.stats.cpu_s, 100.0 * j.stats.health_cpu_s / j.stats.cpu_s);
    std::cout << line;
    for (const std::string& f : j.outputs) std::cout << "  " << f << '\n';
    if (j.stats.divergences > 0)
      std::cout << "  warning: " << j.stats.divergences << " divergent step(s), reset to the equilibrium\n";
    simulated += j.stats.simulated_s;
    cpu += j.stats.cpu_s;
    sink_cpu += j.stats.sink_cpu_s;
    health_cpu += j.stats.health_cpu_s;
  }
  if (cpu > 0.0)
    std::cout << "total: " << simulated << " s simulated in " << cpu << " s of CPU on " << threads
              << " thread(s): " << simulated / cpu << "x real time per core, output " << 100.0 * sink_cpu / cpu
              << "% of it, health analysis " << 100.0 * health_cpu / cpu << "%\n";
  if (failed > 0) throw std::runtime_error(std::to_string(failed) + " scenario(s) failed");
}

}  // namespace

void register_generate_command(CLI::App& app) {
  auto o = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Synthetic vibration datasets from scenario files (docs/scenarios.md, docs/datasets.md): rosbag with the "
      "live node's topics and labels, or NPY/CSV with a JSON sidecar; faster than real time, one thread per "
      "scenario, deterministic per seed");
  cmd->add_option("scenarios", o->scenarios, "Scenario files (YAML)")->required()->type_name("SCENARIO.yaml");
  cmd->add_option("--out", o->out_dir, "Output directory (created if missing)")->required()->type_name("DIR");
  cmd->add_option("--format", o->formats, "Output formats: bag, npy, csv (several: --format bag,npy)")
      ->delimiter(',')
      ->type_name("FORMAT")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of every random source (default: each scenario's seed)")
      ->type_name("N")
      ->check(non_negative_number());
  add_number_option(cmd, "--duration-s", &o->duration_s, "S", "Simulated time (default: each scenario's duration_s)")
      ->check(positive_number())
      ->check(CLI::Range(0.0, kMaxScenarioDurationS));  // as a scenario file's duration_s
  CLI::Option* temperature = add_ring_temperature_option(
      cmd, &o->ring_temperature_difference_K,
      "Inner minus outer ring temperature, K, held for the whole run instead of each scenario's "
      "ring_temperature_difference time line (docs/model.md 3.7)");
  cmd->add_option("--threads", o->threads, "Scenarios run at once (default: hardware concurrency)")
      ->type_name("N")
      ->check(positive_number());
  add_number_option(cmd, "--label-rate", &o->label_rate_hz, "HZ", "Rate of the scenario_state labels")
      ->check(positive_number());
  add_number_option(cmd, "--ball-loads-rate", &o->ball_loads_rate_hz, "HZ", "Rate of ball_loads in the bag")
      ->check(positive_number());
  add_number_option(cmd, "--health-rate", &o->health_rate_hz, "HZ",
                    "Rate of the health reports in the bag (condition indicators of the last 2 s; 0: none)")
      ->check(non_negative_number());
  cmd->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  cmd->add_flag("--allow-long-run", o->allow_long_run,
                "Start a run estimated (from a short probe) to take over an hour of wall time");
  cmd->callback([o, temperature] {
    o->ring_temperature_given = temperature->count() > 0;
    run(*o);
  });
}

}  // namespace bearing_sim::tool
