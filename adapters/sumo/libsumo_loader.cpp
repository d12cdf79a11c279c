// The program's side of the libsumo module (libsumo_module.hpp): the libsumo factories,
// whose simulators load orchestrator-libsumo.so from beside the program on first use.
#include <dlfcn.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "libsumo_build_stamp.hpp"
#include "libsumo_module.hpp"
#include "sumo_ego_control.hpp"

namespace orch {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleName = "orchestrator-libsumo.so";
constexpr const char* kStandInFolder = "libsumo-stubs";

// ORCH_LIBSUMO_MODULE names another file (an installed program whose module lives
// elsewhere); otherwise the module sits beside the program.
fs::path module_path() {
  if (const char* given = std::getenv("ORCH_LIBSUMO_MODULE"); given && *given) return given;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path(kModuleName) : self.parent_path() / kModuleName;
}

// Debian's libsumocpp.so is built from SUMO's GUI sources too and names FFmpeg, GDAL and
// OpenSceneGraph: with their own dependencies ~140 of the ~220 libraries it would load, and
// most of the symbol relocations that made loading it the larger part of a short run's time
// (docs/performance.md, "Start-up of a libsumo run"). A run starts libsumo without a GUI and
// never calls them. The build writes stand-ins of the same sonames beside the module
// (cmake/libsumo_stubs.py: exactly the symbols libsumocpp.so takes from each, every function
// aborting with its name); loaded first, they take those libraries' place, since the dynamic
// loader matches a needed library by soname against the ones already loaded.
// ORCH_LIBSUMO_ALL_LIBRARIES=1 loads the real ones.
std::vector<void*> load_stand_ins(const fs::path& module) {
  std::vector<void*> handles;
  if (const char* all = std::getenv("ORCH_LIBSUMO_ALL_LIBRARIES"); all && *all && std::strcmp(all, "0") != 0)
    return handles;
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(module.parent_path() / kStandInFolder, ec))
    if (entry.is_regular_file(ec) && entry.path().filename().string().rfind("lib", 0) == 0) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files)
    if (void* h = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL)) handles.push_back(h);
  return handles;
}

const LibsumoModule& load_module() {
  static const LibsumoModule* module = nullptr;
  static std::once_flag once;
  std::call_once(once, [] {
    const fs::path path = module_path();
    // RTLD_NOW: a symbol the program lacks is an error here, not a crash mid-run.
    std::vector<void*> stand_ins = load_stand_ins(path);
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle && !stand_ins.empty()) {
      // Stand-ins that no longer fit this libsumocpp.so (a newer SUMO names other symbols):
      // load the real libraries instead.
      for (void* h : stand_ins) dlclose(h);
      handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    }
    if (!handle)
      throw SimulationError(fmt::format("the libsumo backend could not be loaded from {}: {} (build the target "
                                        "orchestrator-libsumo, or choose --backend traci)",
                                        path.string(), dlerror()));
    using Entry = const LibsumoModule* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, "orch_libsumo_module"));
    if (!entry) throw SimulationError(fmt::format("{} is not the orchestrator's libsumo module: {}", path.string(), dlerror()));
    const LibsumoModule* m = entry();
    if (m->abi != kLibsumoModuleAbi || std::strcmp(m->build, ORCH_LIBSUMO_BUILD_STAMP) != 0)
      throw SimulationError(fmt::format(
          "{} belongs to another build of the orchestrator (build {} here, {} there): put the module built with this "
          "program beside it (or name it with ORCH_LIBSUMO_MODULE), or choose --backend traci",
          path.string(), ORCH_LIBSUMO_BUILD_STAMP, m->abi == kLibsumoModuleAbi ? m->build : "of an older interface"));
    module = m;  // never unloaded: libsumo keeps its simulation in static state
  });
  return *module;
}

// Loads the module when the run starts SUMO, so that a missing module ends the run like
// any other failure to start SUMO: verdict error in result.json, with the reason.
class LibsumoOnDemand final : public Simulator {
 public:
  explicit LibsumoOnDemand(SumoBackendOptions options) : options_(std::move(options)) {}
  void start(const SimulatorConfig& config) override { loaded().start(config); }
  void apply(const std::vector<sim::Command>& commands) override { loaded().apply(commands); }
  void advance() override { loaded().advance(); }
  sim::WorldSnapshot read(const std::vector<sim::TrackedActor>& actors) override { return loaded().read(actors); }
  double time() override { return loaded().time(); }
  [[nodiscard]] std::string backend() const override { return "libsumo"; }
  std::string version() override { return loaded().version(); }
  void close() override {
    if (inner_) inner_->close();
  }

 private:
  Simulator& loaded() {
    if (!inner_) inner_ = load_module().make_simulator(options_);
    return *inner_;
  }
  SumoBackendOptions options_;
  std::unique_ptr<Simulator> inner_;
};

// The ego plug-in's SUMO side, loaded at its first use (the run has started SUMO by then).
class EgoControlOnDemand final : public traci::EgoWorld {
 public:
  void new_step() override { loaded().new_step(); }
  void take_over_ego() override { loaded().take_over_ego(); }
  [[nodiscard]] bool supports(traci::Domain domain, int variable) const override {
    return loaded().supports(domain, variable);
  }
  bool exists(traci::Domain domain, const std::string& id) override { return loaded().exists(domain, id); }
  traci::Value read(traci::Domain domain, int variable, const std::string& id,
                    const std::optional<traci::Value>& parameter) override {
    return loaded().read(domain, variable, id, parameter);
  }
  std::vector<std::string> objects_in_range(traci::Domain centre_domain, const std::string& centre,
                                            traci::Domain context, double range,
                                            const std::vector<int>& variables) override {
    return loaded().objects_in_range(centre_domain, centre, context, range, variables);
  }
  void command(const std::string& vehicle, const traci::EgoCommand& command) override {
    loaded().command(vehicle, command);
  }

 private:
  traci::EgoWorld& loaded() const {
    if (!inner_) inner_ = load_module().make_ego_control();
    return *inner_;
  }
  mutable std::unique_ptr<traci::EgoWorld> inner_;
};

}  // namespace

std::unique_ptr<Simulator> make_libsumo_simulator(const SumoBackendOptions& options) {
  return std::make_unique<LibsumoOnDemand>(options);
}

std::unique_ptr<traci::EgoWorld> make_ego_control_libsumo() { return std::make_unique<EgoControlOnDemand>(); }

}  // namespace orch
