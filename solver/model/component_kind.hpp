#pragma once
// A KIND of optional component (solver/model/component.hpp), registered once in
// component_kinds() (solver/model/component_kind.cpp): everything the rest of the code needs to
// know about an optional feature, so that adding one takes its own files and one
// registration there (docs/components.md):
//  * its scene keys, declared as data (KeyDef, solver/io/key_def.hpp): `refmap keys` and
//    scenes/README.md list them with the core's, and the loader allows them;
//  * a parser from the scene to its own typed options (strings become enums and numbers
//    once, bad input is a SceneError naming the key: exit 2), or, for the solids and the
//    implicit step, whose options the core reads too, one into the core's Config;
//  * a factory that makes the component for a Simulation from those options.
// Order: components are added in registration order, which is the order of their hooks at
// one step point (solver/model/component.hpp) and the order of their diagnostics columns.
#include <memory>
#include <string>
#include <vector>

#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/io/key_def.hpp"

namespace refmap {

class Simulation;
class TomlTable;

struct ComponentKind {
  /// Its name in Config::components (and usually its Component::name()).
  std::string name;
  /// Its keys, in reference order. Keys of a table of the core (`output`, `solid`) go right
  /// after the key `after` of that table in the reference ("" or not found: at the end of
  /// the table); keys of its own tables (below) follow their table's entries in order.
  std::vector<KeyDef> keys;
  std::string after;
  /// Tables of its own ([[tracers]], the inline table solid.actuation), each placed in the
  /// reference after the table named by `after` (at the end if there is none).
  struct Table {
    TableDef def;
    std::string after;
  };
  std::vector<Table> tables;
  /// The names of the output files its components write (Component::files): a reused
  /// output directory is cleaned of them whether or not the new run's scene uses the kind.
  std::vector<std::string> files;
  /// Reads its keys: `top` is the scene's top level (TomlTable::sub reads a table of it,
  /// with the same file, overrides and key catalogue), `cfg` the core's options already
  /// parsed (the grid, the boundaries, the solids). Returns its options, or null when the
  /// scene does not use it. Throws SceneError (TomlTable::fail) on bad input.
  std::shared_ptr<const ComponentOptions> (*parse)(const TomlTable& top, const Config& cfg) = nullptr;
  /// Instead of (or besides) `parse`, for a kind whose options the core itself reads: the
  /// solids (their list and shared options: the loader's start checks, contact, the markers
  /// and the Simulation use them) and the implicit velocity step (its constants, read by the
  /// Simulation's limits and passes). Reads the kind's keys into `cfg`; called in
  /// registration order after the core's tables and before any kind's `parse`. Throws
  /// SceneError on bad input.
  void (*configure)(const TomlTable& top, Config& cfg) = nullptr;
  /// Makes the component for `sim` (at the end of its constructor: the flow, the solids
  /// and the boundaries are built) from the options parse returned; null: nothing to add
  /// for this run (e.g. body forces without a body).
  std::unique_ptr<Component> (*make)(const ComponentOptions& options, Simulation& sim) = nullptr;
};

/// The registered kinds, in registration order (solver/model/component_kind.cpp).
const std::vector<ComponentKind>& component_kinds();
/// The kind named `name`; throws std::logic_error if none is.
const ComponentKind& component_kind(const std::string& name);

}  // namespace refmap
