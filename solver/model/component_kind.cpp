// The registry of the optional components' kinds (see solver/model/component_kind.hpp).
#include "solver/model/component_kind.hpp"

#include <stdexcept>

namespace refmap {

// Each kind is defined in its component's own .cpp.
ComponentKind actuation_kind();
ComponentKind tracers_kind();
ComponentKind markers_kind();
ComponentKind wall_stress_kind();
ComponentKind control_volume_forces_kind();
ComponentKind dye_kind();

const std::vector<ComponentKind>& component_kinds() {
  // The order of the hooks at one step point: actuation first (the stress of a step needs
  // A(t + dt)), then the tracers (the velocity of the step's start), the markers.
  static const std::vector<ComponentKind> kinds = {
      actuation_kind(),
      tracers_kind(),
      markers_kind(),
      wall_stress_kind(),
      control_volume_forces_kind(),
      dye_kind(),
  };
  return kinds;
}

const ComponentKind& component_kind(const std::string& name) {
  for (const auto& k : component_kinds())
    if (k.name == name) return k;
  throw std::logic_error("no component kind is named \"" + name + "\" (solver/model/component_kind.cpp)");
}

}  // namespace refmap
