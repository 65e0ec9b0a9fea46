#pragma once
// ROS front end of the bearing model: parameters, topics, dynamic_reconfigure and the
// real-time simulation thread. The physics is all in the core (RingDynamics: the rigid or
// flexible ring).
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>
#include <boost/thread/recursive_mutex.hpp>

#include "bearing_sim/BearingSimConfig.h"
#include "bearing_sim/InjectDefect.h"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim/ros/node_diagnostics.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/health_monitor.hpp"
#include "bearing_sim/runtime/input_validator.hpp"
#include "bearing_sim/runtime/load_ramp.hpp"
#include "bearing_sim/runtime/priority_inheritance_mutex.hpp"
#include "bearing_sim/runtime/realtime_pacer.hpp"
#include "bearing_sim/runtime/sample_divider.hpp"
#include "bearing_sim/runtime/sample_pipeline.hpp"
#include "bearing_sim/runtime/sample_source.hpp"
#include "bearing_sim/runtime/triaxial_sensor.hpp"

namespace bearing_sim {
namespace ros_node {

// Which threads the node may give real-time scheduling (docs/node.md, nodelets).
enum class ThreadScope {
  Process,     // its own process (bearing_sim_node): every thread of it
  OwnThreads,  // a guest in a nodelet manager: only the threads it starts itself
};

// The sink of the per-sample pipeline (shared with `bearing_tool generate`): turns its
// outputs into messages, queued per chunk for their due time.
class BearingSimRos : private runtime::PipelineSink {
 public:
  // Reads the parameters (read_sim_node_parameters) and the bearing file, builds the model
  // at the static equilibrium of the initial load. Throws (ParameterError, ConfigError,
  // LoadNotCarriedError, std::runtime_error) when it cannot start.
  BearingSimRos(ros::NodeHandle nh, ros::NodeHandle pnh, ThreadScope thread_scope = ThreadScope::Process);
  ~BearingSimRos() override;

  void start();  // the simulation thread
  void stop();

 private:
  struct Pending {  // handed from the ROS callbacks to the sim thread
    std::optional<Vector5> load;
    std::optional<double> ring_speed_rad_s;
    std::optional<BearingModel> model;
    std::optional<runtime::OutputSettings> settings;
    // inject_defect / clear_defects in the order called: a spall to add, or nullopt to clear.
    std::vector<std::optional<Spall>> defect_commands;
  };

  void on_load(const geometry_msgs::WrenchStamped::ConstPtr& msg);
  void on_speed(const std_msgs::Float64::ConstPtr& msg);
  void on_reconfigure(BearingSimConfig& config, std::uint32_t level);
  void on_ring_temperature(const std_msgs::Float64::ConstPtr& msg);
  // The running bearing with `changed` settings (clearance, damping, ring temperature), its ball
  // offsets and present spalls kept, if the accepted load is still carried and the integrator
  // can follow it; else nullopt, the reason given to reject_input(input, ...) after `what`.
  std::optional<BearingModel> validated_model(const BearingConfig& changed, const std::string& input,
                                              const std::string& what);
  bool on_inject_defect(InjectDefect::Request& req, InjectDefect::Response& res);
  bool on_clear_defects(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // Logs and counts a refused input and publishes it on `rejected_inputs` (InputRejection):
  // `input` is load, speed, ring_temperature_difference_K or dynamic_reconfigure.
  void reject_input(const std::string& input, const std::string& reason, const ros::Time& input_stamp = ros::Time());
  void publish_model_state();

  // One computed chunk and everything that belongs to its time span (sensor chunks, level,
  // ball loads, health hand-over, /clock), published together, in order, at its due time.
  struct ChunkBundle {
    std::uint64_t last_index = 0;  // of the chunk's last dynamics sample
    std::size_t samples = 0;
    std::vector<std::function<void()>> actions;
  };

  // Sim thread only.
  void run();
  ChunkBundle compute_chunk();
  std::string set_thread_scheduling(int priority);  // description for /diagnostics
  void start_health_worker();  // at SCHED_FIFO 1 (real time, priority > 1), like the process's other threads
  void lock_memory();
  // Publisher thread (real time; the sim thread as fast as possible).
  void run_publisher();
  void publish_bundle(ChunkBundle& bundle);
  void apply_pending();
  // PipelineSink (sim thread, inside compute_chunk): into *bundle_.
  void ideal_chunk(runtime::SampleChunk&& chunk) override;
  void measured_chunk(runtime::SampleChunk&& chunk) override;
  void level(const runtime::SampleSource::Sample& sample, double accel_rms, double window_s) override;
  bool wants_ball_loads() const override;
  bool wants_ring_deformation() const override;
  void ring_deformation(const runtime::SampleSource::Sample& sample,
                        const FlexibleBearing::Deformation& deformation) override;
  void ball_loads(const runtime::SampleSource::Sample& sample, const BearingModel& model,
                  const std::vector<BallState>& balls) override;
  void health_samples(std::vector<float>&& x, std::optional<double> analysis_time_s) override;
  void chunk_end(std::uint64_t last_index, std::size_t samples, const Vector5& load, double ring_speed_rad_s) override;
  void divergence(const std::string& message) override;
  // Health worker thread.
  void publish_health(const runtime::HealthReport& report);
  ros::Time stamp_of(std::uint64_t sample_index) const;

  ros::NodeHandle nh_, pnh_;
  ThreadScope thread_scope_;
  // Parameters (fixed after construction).
  double sample_rate_hz_ = 10000.0;
  runtime::LoadRamp load_ramp_;  // sim thread: a new load over ~load_ramp_s (0: a step)
  bool real_time_ = true;
  bool publish_clock_ = false;
  double max_real_time_factor_ = 0.0;  // not real time: 0 unbounded
  int realtime_priority_ = 0;  // SCHED_FIFO priority of the publisher in real time (sim thread: one less); 0: normal
  bool lock_memory_ = true;    // mlockall in real time
  double lead_s_ = 0.03;       // real time: chunks computed up to this far ahead of their due time
  std::string frame_id_, bearing_frame_id_;
  std::string sensor_description_;     // "sensor: <name>" or "ideal ring acceleration"
  double measured_rate_hz_ = 10000.0;  // of `vibration`, L and health: the sensor's output rate, or sample_rate_hz_
  runtime::InputLimits limits_;
  std::optional<runtime::OutputSettings> accepted_settings_;  // last good reconfigure output settings

  // ROS side (spinner thread only): the latest accepted inputs and model, for validation.
  std::unique_ptr<BearingModel> validation_model_;
  Vector5 accepted_load_ = Vector5::Zero();
  double accepted_speed_rad_s_ = 0.0;
  double accepted_max_pressure_Pa_ = 0.0;
  double substeps_ = 0.0;  // internal steps per sample

  // Priority inheritance: the ROS callbacks (normal priority) hold it while the SCHED_FIFO
  // simulation thread may wait for it.
  runtime::PriorityInheritanceMutex pending_mutex_;
  Pending pending_;
  std::atomic<bool> pending_flag_{false};

  // Sim thread state.
  std::unique_ptr<runtime::SamplePipeline> pipeline_;  // its sensor null: `vibration` is the ideal acceleration
  std::unique_ptr<runtime::HealthMonitor> health_;
  ros::Time ros_start_;

  ros::Publisher vibration_pub_, ideal_pub_, level_pub_, ball_loads_pub_, deformation_pub_, clock_pub_, health_pub_;
  ros::Publisher rejected_pub_;  // rejected_inputs (spinner thread)
  // header.seq of each topic, set here: roscpp numbers only the serialised copies, and a
  // subscriber in the same nodelet manager gets the message itself (publisher thread; health:
  // the health worker).
  std::uint32_t vibration_seq_ = 0, ideal_seq_ = 0, level_seq_ = 0, ball_loads_seq_ = 0, deformation_seq_ = 0,
                health_seq_ = 0;
  ros::ServiceServer inject_srv_, clear_srv_;
  ros::Subscriber load_sub_, speed_sub_, ring_temperature_sub_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<BearingSimConfig>> reconfigure_server_;

  // Real time: chunks computed ahead (sim thread) waiting for their due time (publisher).
  std::optional<runtime::LeadScheduler> scheduler_;
  std::optional<runtime::RealtimePacer> bounded_pacer_;  // not real time with max_real_time_factor > 0
  runtime::RealtimePacer::Clock::time_point wall_start_;
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;
  std::deque<ChunkBundle> ready_;
  ChunkBundle* bundle_ = nullptr;  // sim thread: the bundle being filled by compute_chunk

  std::atomic<bool> stop_{false};
  std::thread sim_thread_, publisher_thread_;
};

}  // namespace ros_node
}  // namespace bearing_sim
