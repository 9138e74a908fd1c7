// A bounded queue between one producer thread and one consumer thread that hands over
// batches of items, not single items: one lock and one wake-up per batch keeps the cost of
// the hand-over small next to the work per item. The batches form a ring and are reused,
// so items (and the buffers inside them) are allocated once and keep their capacity.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <vector>

namespace vc::predistort {

template <typename Item>
class BatchQueue {
 public:
  struct Batch {
    std::vector<Item> items;  // the first `count` are filled
    std::size_t count = 0;
    bool last = false;        // nothing follows this batch
    std::exception_ptr error; // the producer failed after `count` items (with last)
  };

  BatchQueue(std::size_t batches, std::size_t batch_size) : ring_(batches) {
    for (Batch& b : ring_) b.items.resize(batch_size);
  }

  // Producer: the next batch to fill (emptied), once the consumer has freed it; null if
  // the consumer has given up (cancel).
  Batch* begin_fill() {
    std::unique_lock lock(mutex_);
    freed_.wait(lock, [&] { return cancelled_ || filled_ - taken_ < ring_.size(); });
    if (cancelled_) return nullptr;
    Batch& b = ring_[filled_ % ring_.size()];
    b.count = 0;
    b.last = false;
    b.error = nullptr;
    return &b;
  }
  void end_fill() {
    {
      const std::lock_guard lock(mutex_);
      ++filled_;
    }
    ready_.notify_one();
  }

  // Consumer: the next filled batch, in order.
  Batch& begin_take() {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return taken_ < filled_; });
    return ring_[taken_ % ring_.size()];
  }
  void end_take() {
    {
      const std::lock_guard lock(mutex_);
      ++taken_;
    }
    freed_.notify_one();
  }

  // Consumer: stops the producer at its next begin_fill.
  void cancel() {
    {
      const std::lock_guard lock(mutex_);
      cancelled_ = true;
    }
    freed_.notify_one();
  }

 private:
  std::vector<Batch> ring_;
  std::mutex mutex_;
  std::condition_variable ready_, freed_;
  std::size_t filled_ = 0, taken_ = 0;  // batches handed over and given back, ever
  bool cancelled_ = false;
};

}  // namespace vc::predistort
