// volkins' reload of its machine file in a running LinuxCNC (volkins.reload, issue 46), in two
// halves that share one atomic stage and nothing else:
// - ReloadWorker, a std::thread of rtapi_app (made in rtapi_app_main, joined in rtapi_app_exit):
//   on a request it builds new ModuleSettings from the same module parameters (the machine file
//   and its tables read again), checks they may replace the running ones
//   (reload_incompatibility), computes the new file's checksum and hands them over; it prints
//   every refusal and deletes what the servo thread gives back. All I/O and allocation is here.
// - ReloadSequence, in the servo thread (volkins.update): takes a ready file only at rest (the
//   commanded position still, no rotary joint held), ramps the correction out over ramp-time,
//   swaps the settings pointer at gain 0 (the nominal kinematics, the same for both files: the
//   compatibility check's point), and ramps it back in. No allocation, locks or I/O.
//
// The stage is owned by one side at a time; whoever owns it moves it on (release/acquire):
//   Idle --servo: request--> Requested --worker--> Ready (candidate, checksum) | Refused
//   Refused --servo: acknowledge--> Idle
//   Ready --servo: discard (moving, held)--> Discard --worker: message, delete--> Idle
//   Ready --servo: take--> Taken --servo: retire(old) after the swap--> Retire --worker: delete--> Idle
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "gain_ramp.hpp"
#include "module_settings.hpp"

namespace vc::kins {

enum class ReloadStage : int { Idle, Requested, Ready, Refused, Discard, Taken, Retire };

// Why the servo thread gave a ready file back.
enum class ReloadDiscard : int { Moving, Held };

class ReloadWorker {
 public:
  // Builds the settings of the module's parameters anew (throws with file:line: problem).
  using Build = std::function<std::unique_ptr<ModuleSettings>()>;
  // The checksum of a model's files (machine_checksum; throws if one cannot be read).
  using Checksum = std::function<std::uint32_t(const machine::Model&)>;
  // Prints an error message (rtapi_print_msg in the module), without the "volkins: " prefix.
  using Print = std::function<void(const std::string&)>;

  // Starts the thread; `running` stays the caller's (the worker deletes only what it is given
  // back by retire). poll_ms: how often the thread looks at the stage.
  ReloadWorker(const ModuleSettings* running, Build build, Checksum checksum, Print print, int poll_ms = 5);
  ~ReloadWorker();  // stops and joins the thread; deletes a file not taken or given back
  ReloadWorker(const ReloadWorker&) = delete;
  ReloadWorker& operator=(const ReloadWorker&) = delete;

  // Servo thread (noexcept, atomics only).
  ReloadStage stage() const noexcept { return stage_.load(std::memory_order_acquire); }
  bool request() noexcept;                                        // Idle -> Requested
  void acknowledge_refusal() noexcept;                            // Refused -> Idle
  void discard(ReloadDiscard why) noexcept;                       // Ready -> Discard
  const ModuleSettings* take(std::uint32_t& checksum) noexcept;   // Ready -> Taken: the new settings
  void retire(const ModuleSettings* replaced) noexcept;           // Taken -> Retire: the worker deletes it

 private:
  void run();
  void load();

  std::atomic<ReloadStage> stage_{ReloadStage::Idle};
  std::atomic<bool> stop_{false};
  std::atomic<ReloadDiscard> discarded_{ReloadDiscard::Moving};
  // Handed over with the stage (written before its release, read after its acquire).
  const ModuleSettings* running_;
  ModuleSettings* candidate_ = nullptr;
  std::uint32_t candidate_checksum_ = 0;
  const ModuleSettings* replaced_ = nullptr;
  Build build_;
  Checksum checksum_;
  Print print_;
  int poll_ms_;
  std::thread thread_;
};

// volkins.reload-state.
enum ReloadState : int { kReloadIdle = 0, kReloadReading = 1, kReloadRampingOut = 2, kReloadRampingIn = 3 };

// The servo thread's half: one step per volkins.update.
struct ReloadSequence {
  int state = kReloadIdle;   // volkins.reload-state
  bool failed = false;       // volkins.reload-failed: the last request was refused
  std::int32_t reloads = 0;  // volkins.reloads: files swapped in
  std::uint32_t checksum = 0;  // volkins.checksum: of the active file
  GainRamp ramp{1.0, 0.0};     // the correction's factor for the reload (1 but while swapping)
  bool request_was = false;    // volkins.reload in the last period (a rising edge asks)
  bool wanted = false;         // an edge not handed to the worker yet (it was busy)
  const ModuleSettings* incoming = nullptr;  // taken, not swapped in yet (the caller deletes it at exit)
  std::uint32_t checksum_incoming = 0;       // its checksum

  // One servo period. request: volkins.reload; moving: the commanded position moved in the last
  // period; held: a rotary joint is clamped or on its way back; enable: volkins.enable's ramp
  // (at 0 and at rest the file is swapped at once, no ramp). Swaps `settings` when the ramp is
  // at 0 and returns true then (the caller resets what depended on the old file).
  bool step(ReloadWorker& worker, const ModuleSettings*& settings, bool request, bool moving, bool held,
            const GainRamp& enable, double period_s, double ramp_time_s) noexcept;
};

}  // namespace vc::kins
