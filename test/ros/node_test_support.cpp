#include "node_test_support.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/bearing_config.hpp"

namespace node_test {

bearing_sim::BearingModel ct_model() {
  std::string file;
  ros::param::get("~bearing_file", file);
  return bearing_sim::BearingModel(bearing_sim::load_bearing_config(file));
}

Recorder::Recorder(ros::NodeHandle& nh) {
  vibration_sub_ = nh.subscribe("vibration", 10000, &Recorder::on_chunk, this, ros::TransportHints().tcpNoDelay());
  level_sub_ = nh.subscribe("vibration_level", 1000, &Recorder::on_level, this);
  ball_sub_ = nh.subscribe("ball_loads", 10, &Recorder::on_balls, this);
  diag_sub_ = nh.subscribe("/diagnostics", 100, &Recorder::on_diagnostics, this);
}

bool Recorder::wait_for(const std::function<bool()>& pred, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (pred()) return true;
    }
    ros::WallDuration(0.005).sleep();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  return pred();
}

bool Recorder::wait_for_sample(std::uint64_t index, double timeout_s) {
  return wait_for([&] { return have_samples_ && next_index_ > index; }, timeout_s);
}

bool Recorder::wait_for_levels(std::size_t n, double timeout_s) {
  return wait_for([&] { return levels_.size() >= n; }, timeout_s);
}

std::uint64_t Recorder::next_index() {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_index_;
}

double Recorder::mean_displacement(int c, std::uint64_t from, std::uint64_t to) {
  std::lock_guard<std::mutex> lock(mutex_);
  double s = 0.0;
  for (std::uint64_t i = from; i < to; ++i) s += displacement_[c].at(i - first_index_);
  return s / static_cast<double>(to - from);
}

std::vector<double> Recorder::accel_x(std::uint64_t from, std::uint64_t to) {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::vector<double>(accel_x_.begin() + static_cast<long>(from - first_index_),
                             accel_x_.begin() + static_cast<long>(to - first_index_));
}

double Recorder::max_abs_deviation(int c, double reference, std::uint64_t from, std::uint64_t to) {
  std::lock_guard<std::mutex> lock(mutex_);
  double m = 0.0;
  for (std::uint64_t i = from; i < to; ++i)
    m = std::max(m, std::abs(displacement_[c].at(i - first_index_) - reference));
  return m;
}

std::vector<ChunkArrival> Recorder::chunks() {
  std::lock_guard<std::mutex> lock(mutex_);
  return chunks_;
}

std::vector<bearing_sim::VibrationLevel> Recorder::levels() {
  std::lock_guard<std::mutex> lock(mutex_);
  return levels_;
}

bearing_sim::BallLoads::ConstPtr Recorder::last_ball_loads() {
  std::lock_guard<std::mutex> lock(mutex_);
  return ball_loads_;
}

bool Recorder::diagnostic(const std::string& task, diagnostic_msgs::DiagnosticStatus* out) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = diagnostics_.find(task);
  if (it == diagnostics_.end()) return false;
  *out = it->second;
  return true;
}

bool Recorder::wait_for_new_diagnostics(int n, double timeout_s) {
  const int target = diagnostics_received() + n;
  return wait_for([&] { return diagnostics_count_ >= target; }, timeout_s);
}

int Recorder::diagnostics_received() {
  std::lock_guard<std::mutex> lock(mutex_);
  return diagnostics_count_;
}

std::string Recorder::value(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key) {
  for (const auto& kv : s.values)
    if (kv.key == key) return kv.value;
  return "";
}

int Recorder::worst_level(const std::string& task) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = worst_.find(task);
  return it == worst_.end() ? -1 : it->second;
}

std::uint64_t Recorder::gaps() {
  std::lock_guard<std::mutex> lock(mutex_);
  return gaps_;
}
std::uint64_t Recorder::repeats() {
  std::lock_guard<std::mutex> lock(mutex_);
  return repeats_;
}
std::uint64_t Recorder::non_finite() {
  std::lock_guard<std::mutex> lock(mutex_);
  return non_finite_;
}
std::uint64_t Recorder::first_index() {
  std::lock_guard<std::mutex> lock(mutex_);
  return first_index_;
}

void Recorder::on_chunk(const bearing_sim::VibrationChunk::ConstPtr& msg) {
  const ros::WallTime now = ros::WallTime::now();
  std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t n = msg->accel_x.size();
  if (!have_samples_) {
    have_samples_ = true;
    first_index_ = next_index_ = msg->first_sample;
  }
  if (msg->first_sample > next_index_) {
    ++gaps_;
    return;
  }
  if (msg->first_sample < next_index_) {
    ++repeats_;
    return;
  }
  chunks_.push_back({msg->first_sample, n, msg->header.stamp, now});
  for (std::size_t i = 0; i < n; ++i) {
    const double values[4] = {msg->accel_x[i], msg->displacement_x[i], msg->displacement_y[i], msg->displacement_z[i]};
    for (double v : values) non_finite_ += !std::isfinite(v);
    accel_x_.push_back(values[0]);
    displacement_[0].push_back(values[1]);
    displacement_[1].push_back(values[2]);
    displacement_[2].push_back(values[3]);
  }
  next_index_ += n;
}

void Recorder::on_level(const bearing_sim::VibrationLevel::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  levels_.push_back(*msg);
}

void Recorder::on_balls(const bearing_sim::BallLoads::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  ball_loads_ = msg;
}

void Recorder::on_diagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++diagnostics_count_;
  for (const auto& s : msg->status) {
    const auto colon = s.name.rfind(": ");
    if (s.name.find("bearing_sim_node") == std::string::npos || colon == std::string::npos) continue;
    const std::string task = s.name.substr(colon + 2);
    diagnostics_[task] = s;
    auto it = worst_.find(task);
    if (it == worst_.end() || s.level > it->second) worst_[task] = s.level;
  }
}

double spectral_amplitude(const std::vector<double>& x, double f, double fs) {
  double re = 0.0, im = 0.0;
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n - 1));
    const double p = 2.0 * M_PI * f * static_cast<double>(i) / fs;
    re += w * x[i] * std::cos(p);
    im -= w * x[i] * std::sin(p);
  }
  return 4.0 * std::hypot(re, im) / static_cast<double>(n);
}

geometry_msgs::WrenchStamped wrench(const Vector5& l) {
  geometry_msgs::WrenchStamped w;
  w.header.stamp = ros::Time::now();
  w.header.frame_id = "bearing";
  w.wrench.force.x = l[0];
  w.wrench.force.y = l[1];
  w.wrench.force.z = l[2];
  w.wrench.torque.x = l[3];
  w.wrench.torque.y = l[4];
  return w;
}

std_msgs::Float64 speed(double rad_s) {
  std_msgs::Float64 m;
  m.data = rad_s;
  return m;
}

Recorder& recorder() {
  static ros::NodeHandle nh;
  static Recorder r(nh);
  return r;
}

}  // namespace node_test
