// The registry of the optional components' kinds (see solver/model/component_kind.hpp).
#include "solver/model/component_kind.hpp"

#include <stdexcept>

namespace refmap {

// The registered kinds, ONE LINE EACH: a new component adds X(name) here and defines
// `ComponentKind name_kind()` in its own .cpp. The order is that of their hooks at one step
// point: actuation first (the stress of a step needs A(t + dt)), then the tracers (the
// velocity of the step's start), the markers. The first four kinds only read keys (their
// components are made by the Simulation, before all of these): the solids' and the implicit
// step's into the Config (ComponentKind::configure; the rigid bodies' keys are read by the
// solids' parser, at their place in each [[solid]]), contact's into its options
// (solver/components/contact_component.hpp).
#define REFMAP_COMPONENT_KINDS(X) \
  X(solids)                       \
  X(rigid_bodies)                 \
  X(implicit_velocity_step)       \
  X(contact)                      \
  X(actuation)                    \
  X(tracers)                      \
  X(markers)                      \
  X(wall_stress)                  \
  X(control_volume_forces)        \
  X(dye)

#define REFMAP_DECLARE_KIND(name) ComponentKind name##_kind();
REFMAP_COMPONENT_KINDS(REFMAP_DECLARE_KIND)
#undef REFMAP_DECLARE_KIND

const std::vector<ComponentKind>& component_kinds() {
#define REFMAP_CALL_KIND(name) name##_kind(),
  static const std::vector<ComponentKind> kinds = {REFMAP_COMPONENT_KINDS(REFMAP_CALL_KIND)};
#undef REFMAP_CALL_KIND
  return kinds;
}

const ComponentKind& component_kind(const std::string& name) {
  for (const auto& k : component_kinds())
    if (k.name == name) return k;
  throw std::logic_error("no component kind is named \"" + name + "\" (solver/model/component_kind.cpp)");
}

}  // namespace refmap
