#include "bearing_sim/runtime/health_monitor.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"

namespace bearing_sim {
namespace runtime {
namespace {

double equivalent_load_N(const BearingConfig& config, const Vector5& load) {
  return equivalent_dynamic_load(config, std::hypot(load[0], load[1]), std::abs(load[2])).load_N;
}

// Nominal size now; the core caps the depth a ball reaches at width^2 / (4 d) when it rolls.
DefectNow defect_now(const Spall& s, double time_s) {
  DefectNow d;
  d.spall = s;
  d.age_s = std::max(0.0, time_s - s.created_at_s);
  d.width_m = s.width_m + s.width_growth_m_per_s * d.age_s;
  d.depth_m = s.depth_m + s.depth_growth_m_per_s * d.age_s;
  return d;
}

}  // namespace

HealthMonitor::HealthMonitor(BearingModel model, const Vector5& load, double ring_speed_rad_s, HealthSettings settings,
                             Callback callback)
    : settings_(std::move(settings)), callback_(std::move(callback)), load_(load), ring_speed_rad_s_(ring_speed_rad_s) {
  if (!(settings_.sample_rate_hz > 0.0) || !std::isfinite(settings_.sample_rate_hz))
    throw InvalidInputError("health: the sample rate must be > 0 Hz");
  if (!(settings_.window_s > 0.0) || !std::isfinite(settings_.window_s))
    throw InvalidInputError("health: the window must be > 0 s");
  window_samples_ = static_cast<std::size_t>(std::llround(settings_.window_s * settings_.sample_rate_hz));
  if (window_samples_ < 64) throw InvalidInputError("health: the window must hold at least 64 samples");
  settings_.analysis.window_s = 0.0;  // we hand over exactly the window
  ring_.assign(window_samples_, 0.0);
  spalls_ = model.imperfections().spalls();
  model_ = std::make_shared<const BearingModel>(std::move(model));
  double life_million_rev = 0.0;
  try {
    life_million_rev = reference_life(*model_, solve_static(*model_, load).balls, settings_.life).life_million_rev;
    // Also the worker's cache: its first analysis at this load does not solve it again.
    reference_model_ = model_;
    reference_load_ = load;
    reference_life_million_rev_ = life_million_rev;
  } catch (const LoadNotCarriedError&) {
    // A load the static solution cannot take: ISO 281's L10 until an analysis succeeds.
    life_million_rev = basic_rating_life(model_->config(), load, ring_speed_rad_s, settings_.life).life_million_rev;
  }
  life_ = {load, equivalent_load_N(model_->config(), load), life_million_rev};
}

double HealthMonitor::life_now(const Vector5& load) const {
  if (load == life_.load) return life_.life_million_rev;
  const double p_now = equivalent_load_N(model_->config(), load);
  if (p_now > 0.0 && life_.equivalent_load_N > 0.0)
    return life_.life_million_rev * std::pow(life_.equivalent_load_N / p_now, 3.0);
  return life_.life_million_rev;
}

HealthMonitor::~HealthMonitor() { stop(); }

void HealthMonitor::start() {
  if (thread_.joinable()) return;
  {
    std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
    stop_ = false;
  }
  thread_ = std::thread([this] { worker(); });
}

void HealthMonitor::stop() {
  {
    std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void HealthMonitor::push(const float* samples, std::size_t n) {
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  for (std::size_t i = 0; i < n; ++i) {
    ring_[ring_next_] = samples[i];
    if (++ring_next_ == ring_.size()) ring_next_ = 0;
  }
  pushed_ += n;
}

void HealthMonitor::add_operation(const Vector5& load, double ring_speed_rad_s, double dt_s) {
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  // The load was validated (finite, within limits) before it reached the dynamics.
  miner_.add(life_now(load), ring_speed_rad_s, dt_s);
  load_ = load;
  ring_speed_rad_s_ = ring_speed_rad_s;
}

void HealthMonitor::set_defects(const std::vector<Spall>& spalls) {
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  spalls_ = spalls;
}

void HealthMonitor::set_model(const BearingModel& model) {
  auto copy = std::make_shared<const BearingModel>(model);
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  model_ = std::move(copy);
}

void HealthMonitor::request_analysis(double end_time_s) {
  {
    std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
    requested_end_time_s_ = end_time_s;
  }
  wake_.notify_one();
}

std::uint64_t HealthMonitor::samples_pushed() const {
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  return pushed_;
}

std::uint64_t HealthMonitor::analyses() const {
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  return analyses_;
}

HealthMonitor::Snapshot HealthMonitor::take_snapshot(double end_time_s) {
  Snapshot s;
  s.window.reserve(window_samples_);
  std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
  s.end_sample = pushed_;
  s.end_time_s = end_time_s;
  if (pushed_ >= window_samples_) {  // oldest first
    s.window.insert(s.window.end(), ring_.begin() + static_cast<long>(ring_next_), ring_.end());
    s.window.insert(s.window.end(), ring_.begin(), ring_.begin() + static_cast<long>(ring_next_));
  }
  s.load = load_;
  s.ring_speed_rad_s = ring_speed_rad_s_;
  s.spalls = spalls_;
  s.miner_damage = miner_.damage();
  s.remaining_s = miner_.remaining_life_s();
  s.operated_s = miner_.elapsed_s();
  s.revolutions = miner_.revolutions();
  s.model = model_;
  return s;
}

HealthReport HealthMonitor::analyse(Snapshot& s) {
  HealthReport r;
  r.end_sample = s.end_sample;
  r.end_time_s = s.end_time_s;
  r.load = s.load;
  r.ring_speed_rad_s = s.ring_speed_rad_s;
  r.miner_damage = s.miner_damage;
  r.remaining_life_hours = s.remaining_s / 3600.0;
  r.operated_s = s.operated_s;
  r.revolutions = s.revolutions;
  for (const Spall& spall : s.spalls) r.defects.push_back(defect_now(spall, s.end_time_s));
  const BearingModel& model = *s.model;
  try {
    r.frequencies = bearing_frequencies(model, s.ring_speed_rad_s);
    r.iso281 = basic_rating_life(model.config(), s.load, s.ring_speed_rad_s, settings_.life);
    if (reference_model_ != s.model || reference_load_ != s.load) {
      const StaticSolution st = solve_static(model, s.load);
      reference_life_million_rev_ = reference_life(model, st.balls, settings_.life).life_million_rev;
      reference_model_ = s.model;
      reference_load_ = s.load;
      std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
      life_ = {s.load, equivalent_load_N(model.config(), s.load), reference_life_million_rev_};
    }
    r.reference_life_million_rev = reference_life_million_rev_;
    r.reference_life_hours = life_hours(reference_life_million_rev_, s.ring_speed_rad_s);
    if (s.window.empty()) {
      r.error = "collecting the first " + std::to_string(settings_.window_s) + " s window";
      return r;
    }
    r.indicators = analyze_vibration(s.window, settings_.sample_rate_hz, r.frequencies, settings_.analysis);
    r.analysed = true;
  } catch (const std::exception& e) {
    r.analysed = false;
    r.error = std::string("analysis failed: ") + e.what();
  }
  return r;
}

HealthReport HealthMonitor::analyze_now(double end_time_s) {
  Snapshot s = take_snapshot(end_time_s);
  return analyse(s);
}

void HealthMonitor::worker() {
  // The analysis takes tens of ms of CPU and is not real time: never inherit a real-time
  // policy from the thread that started it (at SCHED_FIFO it would hold off the node's other
  // threads of the same priority for the whole analysis).
  const sched_param normal{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  for (;;) {
    double end_time_s = 0.0;
    {
      std::unique_lock<PriorityInheritanceMutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || requested_end_time_s_.has_value(); });
      if (stop_) return;
      end_time_s = *requested_end_time_s_;
      requested_end_time_s_.reset();
    }
    HealthReport report = analyze_now(end_time_s);
    {
      std::lock_guard<PriorityInheritanceMutex> lock(mutex_);
      ++analyses_;
    }
    if (callback_) callback_(report);
  }
}

}  // namespace runtime
}  // namespace bearing_sim
