#pragma once
// `run --realtime FACTOR`: the run advances no faster than FACTOR times wall-clock time
// (1 = real time), for hardware in the loop or an ego stack that needs it. A decorator
// around any Simulator: the scenario logic never sees the clock (simulated time stays the
// only time it knows), and without --realtime nothing waits.
#include <algorithm>
#include <chrono>
#include <thread>

#include "run/simulator.hpp"

namespace orch {

class PacedSimulator final : public Simulator {
 public:
  PacedSimulator(Simulator& inner, double factor) : inner_(inner), factor_(factor) {}

  void start(const SimulatorConfig& config) override {
    inner_.start(config);
    step_ = config.step;
    steps_ = 0;
    origin_ = std::chrono::steady_clock::now();
  }
  void apply(const std::vector<sim::Command>& commands) override { inner_.apply(commands); }
  // After each step, waits until its simulated time is due; a step that took longer is not
  // made up for by skipping waits later (the run falls behind, it does not rush).
  void advance() override {
    inner_.advance();
    ++steps_;
    // Clamped to a century: a duration in nanoseconds overflows its 64 bits past ~292 years.
    const double seconds = std::min(static_cast<double>(steps_) * step_ / factor_, 3.2e9);
    const auto due = origin_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(seconds));
    const auto now = std::chrono::steady_clock::now();
    if (due > now) {
      std::this_thread::sleep_until(due);
    } else {
      origin_ += now - due;
    }
  }
  sim::WorldSnapshot read(const std::vector<sim::TrackedActor>& actors) override { return inner_.read(actors); }
  double time() override { return inner_.time(); }
  [[nodiscard]] std::string backend() const override { return inner_.backend(); }
  std::string version() override { return inner_.version(); }
  void close() override { inner_.close(); }

 private:
  Simulator& inner_;
  double factor_;
  double step_ = 0.05;
  long long steps_ = 0;
  std::chrono::steady_clock::time_point origin_;
};

}  // namespace orch
