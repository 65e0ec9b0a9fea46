// A consumer of bearing_sim's vibration on LCM that knows nothing of ROS (docs/lcm.md):
// subscribes to the vibration channel and prints, for every second of samples, the RMS
// (about the mean) of accel_x and the vibration acceleration level L. Checks that
// first_sample is contiguous and restarts the second after a gap.
//
//   lcm_consumer_example [--url udpm://239.255.76.67:7667?ttl=0] [--channel BEARING_VIBRATION]
//                        [--seconds N] [--idle-exit-s S]
//   lcm_consumer_example --url 'file:///tmp/run.lcm?speed=0'   # a log, as fast as possible
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>

#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim_lcm/vibration_chunk_t.hpp"

namespace {

class PerSecond {
 public:
  explicit PerSecond(long max_lines) : max_lines_(max_lines) {}

  void on_chunk(const lcm::ReceiveBuffer*, const std::string&, const bearing_sim_lcm::vibration_chunk_t* msg) {
    if (have_next_ && msg->first_sample != next_sample_) {
      std::printf("gap: expected sample %lld, got %lld; restarting the second\n", static_cast<long long>(next_sample_),
                  static_cast<long long>(msg->first_sample));
      ++gaps_;
      window_.clear();
    }
    have_next_ = true;
    next_sample_ = msg->first_sample + msg->num_samples;
    const std::size_t per_second = static_cast<std::size_t>(msg->sample_rate + 0.5);
    for (std::int32_t i = 0; i < msg->num_samples; ++i) {
      if (window_.empty())  // time of this second's first sample, from the chunk's exact stamp
        window_start_s_ = static_cast<double>(msg->header.stamp_sec) +
                          1e-9 * static_cast<double>(msg->header.stamp_nsec) +
                          static_cast<double>(i) / msg->sample_rate;
      window_.push_back(msg->accel_x[static_cast<std::size_t>(i)]);
      if (window_.size() >= per_second) print();
    }
  }

  bool done() const { return max_lines_ > 0 && lines_ >= max_lines_; }
  long gaps() const { return gaps_; }

 private:
  void print() {
    const double rms = bearing_sim::rms_about_mean(window_, 0, window_.size());
    std::printf("t = %12.6f s  samples %zu  rms(accel_x) = %.6e m/s^2  L = %7.2f dB\n", window_start_s_, window_.size(),
                rms, bearing_sim::vibration_level_db(rms));
    std::fflush(stdout);
    window_.clear();
    ++lines_;
  }

  long max_lines_, lines_ = 0, gaps_ = 0;
  bool have_next_ = false;
  std::int64_t next_sample_ = 0;
  double window_start_s_ = 0.0;
  std::vector<double> window_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Prints RMS and L of bearing_sim's vibration, per second, from LCM"};
  std::string url = "udpm://239.255.76.67:7667?ttl=0", channel = "BEARING_VIBRATION";
  long seconds = 0;
  double idle_exit_s = 0.0;
  app.add_option("--url", url, "LCM URL (a log: file:///path.lcm?speed=0)")->capture_default_str();
  app.add_option("--channel", channel, "vibration channel")->capture_default_str();
  app.add_option("--seconds", seconds, "exit after this many lines; 0: run until stopped")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--idle-exit-s", idle_exit_s, "exit when nothing arrived for this long; 0: never")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);

  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::fprintf(stderr, "lcm_consumer_example: cannot open LCM URL '%s'\n", url.c_str());
    return 1;
  }
  PerSecond consumer(seconds);
  lcm.subscribe(channel, &PerSecond::on_chunk, &consumer);
  double idle_s = 0.0;
  while (!consumer.done()) {
    const int rc = lcm.handleTimeout(100);
    if (rc < 0) break;  // error, or the end of a log
    idle_s = rc == 0 ? idle_s + 0.1 : 0.0;
    if (idle_exit_s > 0.0 && idle_s >= idle_exit_s) break;
  }
  return consumer.gaps() == 0 ? 0 : 2;
}
