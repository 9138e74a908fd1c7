// A bounded ring of batches that pass, in order, through a fixed number of stages, each
// stage on threads of its own (a pipeline): stage 0 fills a batch, stage 1 works on it
// after stage 0, ..., and the last stage gives it back to stage 0 for refilling. A stage may
// have several lanes (threads) that take the batches in turn (lane l of L: batches l, l + L,
// ...); the first and the last stage have one, so batches are filled and emptied in order.
// Handing over batches, not single items, keeps the locking to one lock and one wake-up per
// batch. The batches are reused, so their items (and the buffers inside them) are
// allocated once.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <vector>

namespace vc::predistort {

template <typename Item, typename Header>
class BatchQueue {
 public:
  struct Batch {
    Header header;            // what stage 0 tells the later stages about the batch (set by it)
    std::vector<Item> items;  // the first `count` are valid
    std::size_t count = 0;
    bool last = false;         // nothing follows this batch
    std::exception_ptr error;  // a stage failed after `count` items (with last); later
                               // stages handle those items, then the last one rethrows
   private:
    friend class BatchQueue;
    std::size_t sequence = 0;  // which batch of the stream this is
    int stage = 0;             // the stage it waits for
  };

  // lanes[s]: threads of stage s (lanes.front() and lanes.back() must be 1).
  BatchQueue(std::vector<int> lanes, std::size_t batches, std::size_t batch_size)
      : ring_(batches), lanes_(std::move(lanes)), next_(lanes_.size()), changed_(lanes_.size()) {
    for (Batch& b : ring_) b.items.resize(batch_size);
    for (std::size_t s = 0; s < lanes_.size(); ++s)
      for (int l = 0; l < lanes_[s]; ++l) next_[s].push_back(static_cast<std::size_t>(l));
  }

  // The next batch for `stage` (and its `lane`), once the stage before it is done with it
  // (stage 0: once the last stage is); null if the pipeline was cancelled, or if the stream
  // ended before this lane's next batch. Stage 0 gets it emptied (all but the header).
  Batch* begin(int stage, int lane = 0) {
    const auto s = static_cast<std::size_t>(stage);
    const std::size_t sequence = next_[s][static_cast<std::size_t>(lane)];
    Batch& b = ring_[sequence % ring_.size()];
    std::unique_lock lock(mutex_);
    changed_[s].wait(lock, [&] {
      return cancelled_ || past_end(sequence) || (b.stage == stage && (stage == 0 || b.sequence == sequence));
    });
    if (cancelled_ || past_end(sequence)) return nullptr;
    if (s == 0) {
      b.sequence = sequence;
      b.count = 0;
      b.last = false;
      b.error = nullptr;
    }
    return &b;
  }
  // `stage` (`lane`) is done with the batch begin(stage, lane) gave it.
  void end(int stage, int lane = 0) {
    const auto s = static_cast<std::size_t>(stage);
    std::size_t& sequence = next_[s][static_cast<std::size_t>(lane)];
    const std::size_t next = s + 1 == lanes_.size() ? 0 : s + 1;
    {
      const std::lock_guard lock(mutex_);
      Batch& b = ring_[sequence % ring_.size()];
      if (s == 0 && b.last) end_ = sequence;
      b.stage = static_cast<int>(next);
    }
    sequence += static_cast<std::size_t>(lanes_[s]);
    changed_[next].notify_all();  // only the next stage can go on
  }

  // Stops every stage at its next begin (a stage failed, or the pipeline is left early).
  void cancel() {
    {
      const std::lock_guard lock(mutex_);
      cancelled_ = true;
    }
    for (std::condition_variable& c : changed_) c.notify_all();
  }

 private:
  bool past_end(std::size_t sequence) const { return end_ != kOpen && sequence > end_; }

  static constexpr std::size_t kOpen = static_cast<std::size_t>(-1);
  std::vector<Batch> ring_;
  std::vector<int> lanes_;
  std::vector<std::vector<std::size_t>> next_;  // per stage and lane: its next batch
  std::size_t end_ = kOpen;                     // sequence of the last batch, once filled
  std::mutex mutex_;
  std::vector<std::condition_variable> changed_;  // per stage: a batch may be ready for it
  bool cancelled_ = false;
};

}  // namespace vc::predistort
