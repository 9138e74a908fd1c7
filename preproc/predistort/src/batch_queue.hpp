// A bounded ring of batches that pass, in order, through a fixed number of stages, each
// stage on a thread of its own (a pipeline): stage 0 fills a batch, stage 1 works on it
// after stage 0, ..., and the last stage gives it back to stage 0 for refilling. Handing
// over batches, not single items, keeps the locking to one lock and one wake-up per batch.
// The batches are reused, so their items (and the buffers inside them) are allocated once.
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
    std::vector<Item> items;  // the first `count` are valid
    std::size_t count = 0;
    bool last = false;        // nothing follows this batch
    std::exception_ptr error; // a stage failed after `count` items (with last); later
                              // stages handle those items, then the last one rethrows
  };

  BatchQueue(int stages, std::size_t batches, std::size_t batch_size)
      : ring_(batches), done_(static_cast<std::size_t>(stages), 0) {
    for (Batch& b : ring_) b.items.resize(batch_size);
  }

  // The next batch for `stage`, once the stage before it is done with it (stage 0: once
  // the last stage is); null if the pipeline was cancelled. Stage 0 gets it emptied.
  Batch* begin(int stage) {
    const auto s = static_cast<std::size_t>(stage);
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return cancelled_ || available(s); });
    if (cancelled_) return nullptr;
    Batch& b = ring_[done_[s] % ring_.size()];
    if (s == 0) {
      b.count = 0;
      b.last = false;
      b.error = nullptr;
    }
    return &b;
  }
  // `stage` is done with the batch begin(stage) gave it.
  void end(int stage) {
    {
      const std::lock_guard lock(mutex_);
      ++done_[static_cast<std::size_t>(stage)];
    }
    changed_.notify_all();
  }

  // Stops every stage at its next begin (a stage failed, or the pipeline is left early).
  void cancel() {
    {
      const std::lock_guard lock(mutex_);
      cancelled_ = true;
    }
    changed_.notify_all();
  }

 private:
  bool available(std::size_t s) const {
    if (s == 0) return done_[0] - done_.back() < ring_.size();
    return done_[s] < done_[s - 1];
  }

  std::vector<Batch> ring_;
  std::vector<std::size_t> done_;  // batches each stage has finished, ever
  std::mutex mutex_;
  std::condition_variable changed_;
  bool cancelled_ = false;
};

}  // namespace vc::predistort
