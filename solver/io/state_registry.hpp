#pragma once
// The persistent state of a run: every array and number that carries information from one
// step to the next, registered once by whoever owns it (the Simulation for the flow, each
// solid, each component). Checkpoint save and load iterate this one list
// (solver/model/checkpoint.cpp), so a component's state is checkpointed by construction and a
// resumed run continues bit for bit as long as everything a step reads from the previous
// one is registered. Scratch arrays that each step overwrites before reading are not.
//
// Records are written and read in registration order; each carries its tag, which the
// reader checks (solver/io/checkpoint_io.hpp), so a checkpoint of another scene layout fails
// naming the record it expected.
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/field.hpp"

namespace refmap {

class CheckpointWriter;
class CheckpointReader;

class StateRegistry {
 public:
  using Save = std::function<void(CheckpointWriter&)>;
  using Load = std::function<void(CheckpointReader&)>;

  /// A field, whole (shape, ghosts and padding). Registered fields must outlive the registry.
  void add_field(const std::string& tag, Field& f);
  void add_value(const std::string& tag, double& v);
  /// An integer of any width, stored as 64 bits.
  template <class Int>
  void add_count(const std::string& tag, Int& v) {
    static_assert(std::is_integral_v<Int>);
    add_count_impl(tag, [&v] { return std::int64_t(v); }, [&v](std::int64_t x) { v = Int(x); });
  }
  void add_values(const std::string& tag, std::vector<double>& v);
  /// An owner's own records (variable layout: windows, event logs), written and read by it.
  void add_record(const std::string& tag, Save save, Load load);

  void save(CheckpointWriter& w) const;
  void load(CheckpointReader& r) const;

  /// The registered tags, in order (tests, error messages).
  std::vector<std::string> tags() const;

 private:
  void add_count_impl(const std::string& tag, std::function<std::int64_t()> get,
                      std::function<void(std::int64_t)> set);
  struct Entry {
    std::string tag;
    Save save;
    Load load;
  };
  std::vector<Entry> entries_;
};

}  // namespace refmap
