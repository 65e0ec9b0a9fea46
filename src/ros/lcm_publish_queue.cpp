#include "bearing_sim/ros/lcm_publish_queue.hpp"

#include <algorithm>
#include <utility>

#include <lcm/lcm-cpp.hpp>

namespace bearing_sim {
namespace ros_node {

LcmPublishQueue::LcmPublishQueue(const std::string& url, std::size_t max_queued_bytes)
    : url_(url), max_queued_bytes_(max_queued_bytes), lcm_(std::make_unique<lcm::LCM>(url)) {
  // LCM prints its own reason on stderr; good() is all the C++ API tells.
  if (!lcm_->good())
    throw LcmUrlError("cannot open LCM URL '" + url +
                      "' (unknown provider, bad address or an unwritable file; LCM's reason is on stderr)");
  thread_ = std::thread(&LcmPublishQueue::run, this);
}

LcmPublishQueue::~LcmPublishQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
  lcm_.reset();
}

bool LcmPublishQueue::push(const std::string& channel, std::vector<std::uint8_t>&& bytes) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stats_.queued_bytes + bytes.size() > max_queued_bytes_) {
      ++stats_.dropped;
      return false;
    }
    stats_.queued_bytes += bytes.size();
    stats_.max_queued_bytes_seen = std::max(stats_.max_queued_bytes_seen, stats_.queued_bytes);
    queue_.push_back({channel, std::move(bytes)});
    stats_.queued_messages = queue_.size();
  }
  wake_.notify_one();
  return true;
}

void LcmPublishQueue::flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

LcmPublishStats LcmPublishQueue::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void LcmPublishQueue::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) break;  // stop_ and drained
    Item item = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    const int rc = lcm_->publish(item.channel, item.bytes.data(), static_cast<unsigned int>(item.bytes.size()));
    lock.lock();
    busy_ = false;
    stats_.queued_bytes -= item.bytes.size();
    stats_.queued_messages = queue_.size();
    if (rc == 0) {
      ++stats_.published;
      stats_.bytes_published += item.bytes.size();
    } else {
      ++stats_.failed;
    }
    if (queue_.empty()) idle_.notify_all();
  }
  idle_.notify_all();
}

}  // namespace ros_node
}  // namespace bearing_sim
