#pragma once
// One LCM instance and a thread that publishes encoded messages from a bounded queue, so
// that the ROS callbacks only convert, encode and enqueue (a file:// log or a full socket
// buffer never blocks them). ROS-free.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace lcm {
class LCM;
}

namespace bearing_sim {
namespace ros_node {

// The LCM URL cannot be opened (unknown provider, bad address, unwritable log file).
class LcmUrlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LcmPublishStats {
  std::uint64_t published = 0;  // accepted by lcm_publish
  std::uint64_t failed = 0;     // lcm_publish returned an error
  std::uint64_t dropped = 0;    // refused by push(): the queue was full
  std::uint64_t bytes_published = 0;
  std::size_t queued_messages = 0;
  std::size_t queued_bytes = 0;
  std::size_t max_queued_bytes_seen = 0;
};

class LcmPublishQueue {
 public:
  // Opens `url` (lcm::LCM); throws LcmUrlError naming the URL if LCM refuses it. At most
  // `max_queued_bytes` of messages wait; beyond that push() drops (and counts) the message.
  LcmPublishQueue(const std::string& url, std::size_t max_queued_bytes);
  // Publishes everything still queued, then closes LCM (a file:// log is complete after this).
  ~LcmPublishQueue();
  LcmPublishQueue(const LcmPublishQueue&) = delete;
  LcmPublishQueue& operator=(const LcmPublishQueue&) = delete;

  // Enqueues one encoded message (see encode_lcm); false if dropped because the queue is full.
  bool push(const std::string& channel, std::vector<std::uint8_t>&& bytes);
  // Blocks until the queue is empty and the publisher thread idle.
  void flush();
  LcmPublishStats stats() const;
  const std::string& url() const { return url_; }

 private:
  struct Item {
    std::string channel;
    std::vector<std::uint8_t> bytes;
  };
  void run();

  std::string url_;
  std::size_t max_queued_bytes_;
  std::unique_ptr<lcm::LCM> lcm_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<Item> queue_;
  bool busy_ = false, stop_ = false;
  LcmPublishStats stats_;
  std::thread thread_;
};

}  // namespace ros_node
}  // namespace bearing_sim
