#include "run/roadless_net.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/files.hpp"

namespace orch {

namespace {
// Far from the scenes of real files (which sit within a few kilometres of their origin), so
// that no entity placed by the storyboard is near the parking road.
constexpr double kParkingX = -100000.0, kParkingY = -100000.0;
}  // namespace

std::string parking_road_xodr() {
  return fmt::format(R"(<?xml version="1.0" encoding="UTF-8"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="4" name="orchestrator parking road for scenarios without a road"/>
  <road name="parking" length="{len}" id="{id}" junction="-1">
    <link/>
    <planView>
      <geometry s="0" x="{x}" y="{y}" hdg="0" length="{len}"><line/></geometry>
    </planView>
    <lanes>
      <laneSection s="0">
        <center><lane id="0" type="none" level="false"/></center>
        <right>
          <lane id="-1" type="driving" level="false">
            <width sOffset="0" a="3.5" b="0" c="0" d="0"/>
            <speed sOffset="0" max="50"/>
          </lane>
        </right>
      </laneSection>
    </lanes>
  </road>
</OpenDRIVE>
)",
                     fmt::arg("len", kParkingRoadLength), fmt::arg("id", kParkingRoadId), fmt::arg("x", kParkingX),
                     fmt::arg("y", kParkingY));
}

opendrive::SumoNet roadless_sumo_net(const std::filesystem::path& cache_root, std::filesystem::path& xodr_file) {
  const std::filesystem::path dir = cache_root / "roadless";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw MapError(fmt::format("cannot create {}: {}", dir.string(), ec.message()));
  xodr_file = dir / "parking.xodr";
  write_file_atomically(xodr_file, parking_road_xodr());
  return opendrive::convert_to_sumo_net(xodr_file, cache_root);
}

double parking_place(std::size_t index) {
  return std::fmod(10.0 + 20.0 * static_cast<double>(index), kParkingRoadLength - 20.0);
}

}  // namespace orch
