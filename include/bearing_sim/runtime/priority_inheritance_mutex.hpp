#pragma once
// A mutex with priority inheritance (POSIX PTHREAD_PRIO_INHERIT): while a SCHED_FIFO thread
// waits for it, the normal-priority thread holding it runs at the waiter's priority, so a
// busy machine cannot deschedule the holder and stall the real-time thread (priority
// inversion). Lockable, for std::lock_guard / std::unique_lock / std::condition_variable_any.
#include <pthread.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace bearing_sim {
namespace runtime {

class PriorityInheritanceMutex {
 public:
  PriorityInheritanceMutex() {
    pthread_mutexattr_t attr;
    pthread_mutexattr_init(&attr);
    // Where the protocol is not supported the mutex is an ordinary one: still correct.
    pthread_mutexattr_setprotocol(&attr, PTHREAD_PRIO_INHERIT);
    const int err = pthread_mutex_init(&mutex_, &attr);
    pthread_mutexattr_destroy(&attr);
    if (err != 0) throw std::runtime_error(std::string("pthread_mutex_init: ") + std::strerror(err));
  }
  ~PriorityInheritanceMutex() { pthread_mutex_destroy(&mutex_); }
  PriorityInheritanceMutex(const PriorityInheritanceMutex&) = delete;
  PriorityInheritanceMutex& operator=(const PriorityInheritanceMutex&) = delete;

  void lock() { pthread_mutex_lock(&mutex_); }
  bool try_lock() { return pthread_mutex_trylock(&mutex_) == 0; }
  void unlock() { pthread_mutex_unlock(&mutex_); }

 private:
  pthread_mutex_t mutex_;
};

}  // namespace runtime
}  // namespace bearing_sim
