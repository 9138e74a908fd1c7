#include "reload_worker.hpp"

#include <chrono>
#include <exception>

#include "vc/machine/reload_compatibility.hpp"

namespace vc::kins {

ReloadWorker::ReloadWorker(const ModuleSettings* running, Build build, Checksum checksum, Print print, int poll_ms)
    : running_(running),
      build_(std::move(build)),
      checksum_(std::move(checksum)),
      print_(std::move(print)),
      poll_ms_(poll_ms),
      thread_([this] { run(); }) {}

ReloadWorker::~ReloadWorker() {
  stop_.store(true, std::memory_order_release);
  thread_.join();
  delete candidate_;  // made, not taken (a taken one is the servo thread's or retired below)
  if (stage_.load(std::memory_order_acquire) == ReloadStage::Retire) delete replaced_;
}

bool ReloadWorker::request() noexcept {
  ReloadStage idle = ReloadStage::Idle;
  return stage_.compare_exchange_strong(idle, ReloadStage::Requested, std::memory_order_acq_rel);
}

void ReloadWorker::acknowledge_refusal() noexcept {
  if (stage() == ReloadStage::Refused) stage_.store(ReloadStage::Idle, std::memory_order_release);
}

void ReloadWorker::discard(ReloadDiscard why) noexcept {
  if (stage() != ReloadStage::Ready) return;
  discarded_.store(why, std::memory_order_relaxed);
  stage_.store(ReloadStage::Discard, std::memory_order_release);
}

const ModuleSettings* ReloadWorker::take(std::uint32_t& checksum) noexcept {
  if (stage() != ReloadStage::Ready) return nullptr;
  const ModuleSettings* taken = candidate_;
  checksum = candidate_checksum_;
  candidate_ = nullptr;
  running_ = taken;  // what the next request is compared with
  stage_.store(ReloadStage::Taken, std::memory_order_release);
  return taken;
}

void ReloadWorker::retire(const ModuleSettings* replaced) noexcept {
  if (stage() != ReloadStage::Taken) return;
  replaced_ = replaced;
  stage_.store(ReloadStage::Retire, std::memory_order_release);
}

void ReloadWorker::run() {
  while (!stop_.load(std::memory_order_acquire)) {
    switch (stage()) {
      case ReloadStage::Requested:
        load();
        break;
      case ReloadStage::Discard:
        print_(discarded_.load(std::memory_order_relaxed) == ReloadDiscard::Moving
                   ? "reload refused while an axis moves: reload at rest, e.g. M100 after the moves"
                   : "reload refused while a rotary joint is clamped (or on its way back from its clamp): reload "
                     "with every rotary joint free");
        delete candidate_;
        candidate_ = nullptr;
        stage_.store(ReloadStage::Idle, std::memory_order_release);
        break;
      case ReloadStage::Retire:
        delete replaced_;
        replaced_ = nullptr;
        stage_.store(ReloadStage::Idle, std::memory_order_release);
        break;
      default:
        break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(poll_ms_));
  }
}

void ReloadWorker::load() {
  std::unique_ptr<ModuleSettings> next;
  std::string refusal;
  std::uint32_t checksum = 0;
  try {
    next = build_();
    refusal = machine::reload_incompatibility(running_->model, next->model);
    if (!refusal.empty()) refusal = next->model.path + ": " + refusal;
    else checksum = checksum_(next->model);
  } catch (const std::exception& e) {
    refusal = e.what();
  } catch (...) {
    refusal = "unknown error while loading the machine file";
  }
  if (!refusal.empty()) {
    print_("reload refused: " + refusal + "; the running file stays active");
    stage_.store(ReloadStage::Refused, std::memory_order_release);
    return;
  }
  candidate_ = next.release();
  candidate_checksum_ = checksum;
  stage_.store(ReloadStage::Ready, std::memory_order_release);
}

bool ReloadSequence::step(ReloadWorker& worker, const ModuleSettings*& settings, bool request, bool moving, bool held,
                          const GainRamp& enable, double period_s, double ramp_time_s) noexcept {
  if (request && !request_was) {
    wanted = true;
    failed = false;  // cleared by the next request
  }
  request_was = request;
  bool swapped = false;
  switch (state) {
    case kReloadIdle:
      if (wanted && worker.request()) {
        wanted = false;
        state = kReloadReading;
      }
      break;
    case kReloadReading:
      if (worker.stage() == ReloadStage::Refused) {
        worker.acknowledge_refusal();
        failed = true;
        state = kReloadIdle;
      } else if (worker.stage() == ReloadStage::Ready) {
        if (moving || held) {
          worker.discard(moving ? ReloadDiscard::Moving : ReloadDiscard::Held);
          failed = true;
          state = kReloadIdle;
        } else {
          incoming = worker.take(checksum_incoming);
          // The enable ramp at rest at 0: the correction is off, nothing to ramp.
          state = enable.gain == 0.0 && enable.rate == 0.0 ? kReloadRampingIn : kReloadRampingOut;
          if (state == kReloadRampingIn) ramp = {1.0, 0.0};
        }
      }
      break;
    case kReloadRampingOut:
      ramp.step(0.0, period_s, ramp_time_s);
      break;
    case kReloadRampingIn:
      ramp.step(1.0, period_s, ramp_time_s);
      if (!incoming && ramp.gain == 1.0 && ramp.rate == 0.0) state = kReloadIdle;
      break;
  }
  // At gain 0 and at rest (or with the correction off): the swap, between two kinematics calls.
  const bool ramped_out = state == kReloadRampingOut && ramp.gain == 0.0 && ramp.rate == 0.0;
  if (incoming && (ramped_out || state == kReloadRampingIn)) {
    const ModuleSettings* replaced = settings;
    settings = incoming;
    incoming = nullptr;
    checksum = checksum_incoming;
    ++reloads;
    worker.retire(replaced);
    state = kReloadRampingIn;
    swapped = true;
  }
  return swapped;
}

}  // namespace vc::kins
