#pragma once
// Condition monitoring of the running simulation (docs/node.md, health), ROS-free.
// The simulation thread only appends samples and operating data (short critical sections,
// no analysis, no allocation in steady state); a worker thread, woken by request_analysis()
// (once per simulated second in the node), copies the last window out of the ring buffer
// and runs the core's analyze_vibration, the ISO 281 / reference lives and reports the
// Miner damage the simulation thread has accumulated. The report goes to a callback on
// the worker thread.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bearing_sim/core/bearing_life.hpp"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/runtime/defects_now.hpp"
#include "bearing_sim/runtime/priority_inheritance_mutex.hpp"

namespace bearing_sim {
namespace runtime {

struct HealthSettings {
  double sample_rate_hz = 10000.0;  // of the analysed signal (sensor output or dynamics rate)
  double window_s = 2.0;            // analysed: the last window_s seconds (shortened to an FFT-friendly length)
  AnalysisOptions analysis;         // envelope band, thresholds, zones (window_s there is ignored)
  LifeConfig life;
};

struct HealthReport {
  bool analysed = false;  // false: no complete window yet, or the analysis failed (error)
  std::string error;
  std::uint64_t end_sample = 0;  // index (analysed signal) after the window's last sample
  double end_time_s = 0.0;       // simulated time of the window's last sample
  ConditionIndicators indicators;
  BearingFrequencies frequencies;  // at ring_speed_rad_s
  std::vector<DefectNow> defects;
  // Operating point (at the request) and life.
  Vector5 load = Vector5::Zero();
  double ring_speed_rad_s = 0.0;
  BasicRatingLife iso281;
  double reference_life_million_rev = 0.0;
  double reference_life_hours = 0.0;
  double miner_damage = 0.0;
  double remaining_life_hours = 0.0;
  double operated_s = 0.0;
  double revolutions = 0.0;
};

class HealthMonitor {
 public:
  using Callback = std::function<void(const HealthReport&)>;
  // Throws InvalidInputError for a bad rate or window.
  HealthMonitor(BearingModel model, const Vector5& load, double ring_speed_rad_s, HealthSettings settings,
                Callback callback);
  ~HealthMonitor();
  HealthMonitor(const HealthMonitor&) = delete;
  HealthMonitor& operator=(const HealthMonitor&) = delete;

  void start();  // the worker thread
  void stop();

  // --- simulation thread ---
  // Consecutive samples of the analysed signal (m/s^2).
  void push(const float* samples, std::size_t n);
  // dt_s of operation at this load and speed (Miner damage; the operating point for life
  // and fault frequencies). Cheap: one table look-up.
  void add_operation(const Vector5& load, double ring_speed_rad_s, double dt_s);
  // The spalls present now (after an injection or a clear); simulated time of the change.
  void set_defects(const std::vector<Spall>& spalls);
  // Wakes the worker to analyse the window ending at the last pushed sample, stamped with
  // this simulated time. Never blocks on the analysis; requests made while it is busy
  // collapse into one.
  void request_analysis(double end_time_s);

  // --- any thread ---
  // A new model (clearance or damping changed): used for the next reference life.
  void set_model(const BearingModel& model);
  // The analysis of the current window, synchronously (tests, with the worker not started).
  HealthReport analyze_now(double end_time_s);

  std::uint64_t samples_pushed() const;
  std::uint64_t analyses() const;
  const HealthSettings& settings() const { return settings_; }

 private:
  struct Snapshot {
    std::vector<double> window;
    std::uint64_t end_sample = 0;
    double end_time_s = 0.0;
    Vector5 load = Vector5::Zero();
    double ring_speed_rad_s = 0.0;
    std::vector<Spall> spalls;
    double miner_damage = 0.0, remaining_s = 0.0, operated_s = 0.0, revolutions = 0.0;
    std::shared_ptr<const BearingModel> model;
  };
  Snapshot take_snapshot(double end_time_s);  // locks
  HealthReport analyse(Snapshot& s);          // no lock held
  void worker();

  HealthSettings settings_;
  Callback callback_;
  std::size_t window_samples_ = 0;

  // Priority inheritance: the real-time publisher pushes samples while this normal-priority
  // worker may hold the lock.
  mutable PriorityInheritanceMutex mutex_;  // everything below
  std::condition_variable_any wake_;
  std::vector<double> ring_;  // circular, capacity window_samples_
  std::size_t ring_next_ = 0;
  std::uint64_t pushed_ = 0;
  Vector5 load_ = Vector5::Zero();
  double ring_speed_rad_s_ = 0.0;
  std::vector<Spall> spalls_;
  MinerDamage miner_;
  // The Miner sum's life model is the reference life (the one reported): its value at the
  // load of the last analysis; another load until the next analysis scales it by ISO 281's
  // (P_then / P_now)^3 (solve_static is too slow for the publisher's thread).
  struct LifeAtLoad {
    Vector5 load = Vector5::Constant(std::numeric_limits<double>::quiet_NaN());
    double equivalent_load_N = 0.0;  // ISO 281 P at that load
    double life_million_rev = std::numeric_limits<double>::infinity();
  };
  LifeAtLoad life_;
  double life_now(const Vector5& load) const;  // mutex_ held
  std::shared_ptr<const BearingModel> model_;
  std::optional<double> requested_end_time_s_;
  bool stop_ = false;
  std::uint64_t analyses_ = 0;
  std::thread thread_;

  // Worker only: reference life cache (solve_static is a few ms for the CT bearing).
  Vector5 reference_load_ = Vector5::Constant(std::numeric_limits<double>::quiet_NaN());
  std::shared_ptr<const BearingModel> reference_model_;
  double reference_life_million_rev_ = 0.0;
};

}  // namespace runtime
}  // namespace bearing_sim
