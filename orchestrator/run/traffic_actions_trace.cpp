#include "run/traffic_actions_trace.hpp"

#include <fmt/format.h>

#include <charconv>

#include "run/traffic_trace.hpp"

namespace orch {

TrafficActionsTrace::TrafficActionsTrace(std::filesystem::path dir,
                                         std::function<const openscenario::TrafficBook*()> book)
    : dir_(std::move(dir)), book_(std::move(book)) {}

namespace {

// The serial of a traffic vehicle's SUMO id "traffic<serial>.<n>" (0: not one).
int serial_of(const std::string& id) {
  constexpr std::string_view kPrefix = "traffic";
  if (id.compare(0, kPrefix.size(), kPrefix) != 0) return 0;
  int serial = 0;
  const char* begin = id.data() + kPrefix.size();
  const auto [end, error] = std::from_chars(begin, id.data() + id.size(), serial);
  return error == std::errc() && end != begin ? serial : 0;
}

}  // namespace

void TrafficActionsTrace::step(const StepView& view) {
  const openscenario::TrafficBook* book = book_();
  if (!book || book->all().empty()) return;
  if (!file_) file_.emplace(dir_ / kFile, std::string(TrafficTrace::kBackgroundHeader) + kExtraColumns);
  const double time = view.run.judged().time;
  for (const auto& v : view.snapshot.traffic)
    file_->print(FMT_COMPILE("{:.3f},{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{:.3f},{}\n"), time, v.sumo_id,
                 v.position.x(), v.position.y(), v.heading, v.speed, v.length, v.width, serial_of(v.sumo_id));
  file_->end_step(200);
}

void TrafficActionsTrace::finish(RunResult& /*result*/) noexcept {
  if (file_) file_->flush();
}

}  // namespace orch
