#pragma once
// One module of the pipeline's chain (paper, system diagram): it handles its messages one at a time, in the
// order they were pushed, either on a thread of its own behind a bounded queue or inline in the caller.
// Either way a module sees the same message sequence, so a deterministic module gives the same output;
// threads only let the modules of the chain work at the same time.
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace vilslam {

// Messages waiting in a stage before push() blocks, unless the stage is given another capacity.
constexpr std::size_t kDefaultStageCapacity = 256;

template <typename Message>
class Stage {
 public:
  // threaded: run handle() on a thread of its own; capacity: messages waiting before push() blocks.
  Stage(std::function<void(Message&&)> handle, bool threaded, std::size_t capacity = kDefaultStageCapacity)
      : handle_(std::move(handle)), capacity_(capacity) {
    if (threaded) worker_ = std::thread([this] { work(); });
  }
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;
  // Without finish() (an error elsewhere in the run) the messages still waiting are dropped.
  ~Stage() { stop(/*drain=*/false); }

  // Hands a message to the stage. After the stage failed, messages are dropped (failed() says so).
  void push(Message message) {
    if (!worker_.joinable()) {
      if (!error_) call(std::move(message));
      return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    space_.wait(lock, [this] { return queue_.size() < capacity_ || error_ || closed_; });
    if (error_ || closed_) return;
    queue_.push_back(std::move(message));
    max_depth_ = std::max(max_depth_, queue_.size());
    ready_.notify_one();
  }

  bool failed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_ != nullptr;
  }

  // The most messages that waited at once (0 inline).
  std::size_t max_depth() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_depth_;
  }

  // Waits until every message pushed so far is handled (or the stage failed); the stage goes on taking messages.
  void wait_idle() {
    if (!worker_.joinable()) return;
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return (queue_.empty() && !busy_) || error_; });
  }

  // Waits until every pushed message is handled, then rethrows what handle() threw, if anything.
  void finish() {
    stop(/*drain=*/true);
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void call(Message&& message) {
    try {
      handle_(std::move(message));
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      space_.notify_all();
      idle_.notify_all();
    }
  }

  void work() {
    for (;;) {
      Message message;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ready_.wait(lock, [this] { return !queue_.empty() || closed_; });
        if (queue_.empty()) return;  // closed and drained
        message = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        space_.notify_one();
      }
      if (!failed()) call(std::move(message));
      std::lock_guard<std::mutex> lock(mutex_);
      busy_ = false;
      if (queue_.empty()) idle_.notify_all();
    }
  }

  void stop(bool drain) {
    if (!worker_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
      if (!drain) queue_.clear();
      ready_.notify_all();
      space_.notify_all();
    }
    worker_.join();
  }

  std::function<void(Message&&)> handle_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable space_;
  std::condition_variable idle_;
  std::deque<Message> queue_;
  bool busy_ = false;  // the worker is handling a message
  std::size_t max_depth_ = 0;
  bool closed_ = false;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace vilslam
