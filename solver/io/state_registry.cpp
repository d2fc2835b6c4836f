#include "solver/io/state_registry.hpp"

#include <stdexcept>

#include "solver/io/checkpoint_io.hpp"

namespace refmap {

void StateRegistry::add_record(const std::string& tag, Save save, Load load) {
  // two owners registering the same tag would read each other's records back
  for (const Entry& e : entries_)
    if (e.tag == tag) throw std::logic_error("state '" + tag + "' registered twice");
  entries_.push_back({tag, std::move(save), std::move(load)});
}

void StateRegistry::add_field(const std::string& tag, Field& f) {
  add_record(
      tag, [&f, tag](CheckpointWriter& w) { w.put_field(tag, f); },
      [&f, tag](CheckpointReader& r) { r.get_field(tag, f); });
}

void StateRegistry::add_value(const std::string& tag, double& v) {
  add_record(
      tag, [&v, tag](CheckpointWriter& w) { w.put_f64(tag, v); },
      [&v, tag](CheckpointReader& r) { v = r.get_f64(tag); });
}

void StateRegistry::add_values(const std::string& tag, std::vector<double>& v) {
  add_record(
      tag, [&v, tag](CheckpointWriter& w) { w.put_f64s(tag, v); },
      [&v, tag](CheckpointReader& r) { v = r.get_f64s(tag); });
}

void StateRegistry::add_count_impl(const std::string& tag, std::function<std::int64_t()> get,
                                   std::function<void(std::int64_t)> set) {
  add_record(
      tag, [get, tag](CheckpointWriter& w) { w.put_i64(tag, get()); },
      [set, tag](CheckpointReader& r) { set(r.get_i64(tag)); });
}

void StateRegistry::save(CheckpointWriter& w) const {
  for (const Entry& e : entries_) e.save(w);
}

void StateRegistry::load(CheckpointReader& r) const {
  for (const Entry& e : entries_) e.load(r);
}

std::vector<std::string> StateRegistry::tags() const {
  std::vector<std::string> t;
  for (const Entry& e : entries_) t.push_back(e.tag);
  return t;
}

}  // namespace refmap
