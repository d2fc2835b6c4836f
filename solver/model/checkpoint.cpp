// The state a run continues from: what Simulation::step reads that is not rebuilt from the
// scene. A resumed run must give the same bits as the uninterrupted one, so every array
// that carries information from one step to the next is saved whole (ghosts included);
// scratch arrays that each step overwrites before reading (RK-4 stages, forces, the
// Poisson right-hand side) are not. The byte format is solver/io/checkpoint_io.hpp.
#include <cstring>
#include <string>

#include "solver/model/boundary.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/model/contact.hpp"
#include "solver/components/solids.hpp"
#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

namespace {

template <class T>
void put_pods(CheckpointWriter& w, const std::string& tag, const std::vector<T>& v) {
  w.put_bytes(tag, v.data(), v.size() * sizeof(T));
}

template <class T>
void get_pods(CheckpointReader& r, const std::string& tag, std::vector<T>& v) {
  const auto b = r.get_bytes(tag);
  if (b.size() % sizeof(T)) throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + "' has the wrong size");
  v.resize(b.size() / sizeof(T));
  if (!b.empty()) std::memcpy(v.data(), b.data(), b.size());
}

}  // namespace

void Simulation::save_state(CheckpointWriter& w) const { state_.save(w); }

void Simulation::load_state(CheckpointReader& r) {
  state_.load(r);
  // caches keyed by the step count, and the pressure solver's operator of the restored
  // density (as after the step that wrote it; a prescribed flow solves for no pressure)
  if (solids_) solids_->invalidate_diagnostics();
  ke_step_ = -1;
  if (cfg_.flow != FlowMode::Prescribed) poisson_->setup(poisson_operator());
}

void Solid::save_state(CheckpointWriter& w, const std::string& tag) const {
  const std::int64_t win[4] = {i0_, j0_, ni_, nj_};
  w.put_bytes(tag + ".window", win, sizeof win);
  const std::pair<const char*, const Field*> fields[] = {
      {"xi_x", &xi_x_}, {"xi_y", &xi_y_}, {"phi", &phi_}, {"sxx", &sxx_}, {"sxy", &sxy_}, {"syy", &syy_}};
  for (const auto& [name, f] : fields) w.put_field(tag + "." + name, *f);
  w.put_mask(tag + ".known", known_);
  w.put_f64(tag + ".max_wave_modulus", max_wave_modulus_);
  const std::int64_t counts[5] = {counters_.calls, counters_.cells_filled, counters_.fallbacks, counters_.iterations,
                                  rewindows_};
  w.put_bytes(tag + ".counters", counts, sizeof counts);
}

void Solid::load_state(CheckpointReader& r, const std::string& tag) {
  const auto win = r.get_bytes(tag + ".window");
  std::int64_t v[4];
  if (win.size() != sizeof v) throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + ".window' has the wrong size");
  std::memcpy(v, win.data(), sizeof v);
  i0_ = int(v[0]);
  j0_ = int(v[1]);
  ni_ = int(v[2]);
  nj_ = int(v[3]);
  const std::pair<const char*, Field*> fields[] = {
      {"xi_x", &xi_x_}, {"xi_y", &xi_y_}, {"phi", &phi_}, {"sxx", &sxx_}, {"sxy", &sxy_}, {"syy", &syy_}};
  for (const auto& [name, f] : fields) r.get_field(tag + "." + name, *f);
  if (xi_x_.nx() != ni_ || xi_x_.ny() != nj_ || phi_.nx() != ni_ || phi_.ny() != nj_)
    throw CheckpointError("checkpoint " + r.path() + ": solid " + tag + " window and arrays disagree");
  r.get_mask(tag + ".known", known_);
  max_wave_modulus_ = r.get_f64(tag + ".max_wave_modulus");
  const auto c = r.get_bytes(tag + ".counters");
  std::int64_t n[5];
  if (c.size() != sizeof n) throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + ".counters' has the wrong size");
  std::memcpy(n, c.data(), sizeof n);
  counters_.calls = n[0];
  counters_.cells_filled = n[1];
  counters_.fallbacks = n[2];
  counters_.iterations = n[3];
  rewindows_ = n[4];
}

void Contact::save_state(CheckpointWriter& w) const {
  w.put_f64s("contact.gap_solid", gap_solid_);
  w.put_f64s("contact.gap_wall", gap_wall_);
  put_pods(w, "contact.wall_state", wall_state_);
  // the pairs in contact, a and b interleaved (the N x N table of format 2 is gone)
  std::vector<std::int64_t> touching;
  for (const auto& [a, b] : touching_) { touching.push_back(a); touching.push_back(b); }
  put_pods(w, "contact.touching", touching);
  w.put_f64s("contact.pair_totals", pair_totals_);
  w.put_f64("contact.energy", energy_);
  w.put_f64("contact.U", U_);
  w.put_i64("contact.events", std::int64_t(events_.size()));
  for (const ContactEvent& e : events_) {
    w.put_f64("event.time", e.time);
    w.put_i64("event.solid", e.solid);
    w.put_string("event.event", e.event);
    w.put_f64("event.value", e.value);
    w.put_string("event.with", e.with);
  }
}

void Contact::load_state(CheckpointReader& r) {
  const std::int64_t nsolids = std::int64_t(wall_state_.size());  // the scene's, before loading
  gap_solid_ = r.get_f64s("contact.gap_solid");
  gap_wall_ = r.get_f64s("contact.gap_wall");
  observed_ = true;
  get_pods(r, "contact.wall_state", wall_state_);
  std::vector<std::int64_t> touching;
  get_pods(r, "contact.touching", touching);
  if (touching.size() % 2) throw CheckpointError("checkpoint " + r.path() + ": record 'contact.touching' has the wrong size");
  touching_.clear();
  for (std::size_t k = 0; k < touching.size(); k += 2) {
    const std::int64_t a = touching[k], b = touching[k + 1];
    // sorted pairs a < b of this scene's solids, as save_state wrote them
    if (!(0 <= a && a < b && b < nsolids) || (!touching_.empty() && !(touching_.back() < std::pair<int, int>(int(a), int(b)))))
      throw CheckpointError("checkpoint " + r.path() + ": record 'contact.touching' names impossible pairs");
    touching_.emplace_back(int(a), int(b));
  }
  pair_totals_ = r.get_f64s("contact.pair_totals");
  energy_ = r.get_f64("contact.energy");
  U_ = r.get_f64("contact.U");
  P_ = P_unit_ * U_ * U_;
  const std::int64_t n = r.get_i64("contact.events");
  if (n < 0 || n > (std::int64_t(1) << 32)) throw CheckpointError("checkpoint " + r.path() + ": impossible event count");
  events_.clear();
  for (std::int64_t k = 0; k < n; ++k) {
    ContactEvent e;
    e.time = r.get_f64("event.time");
    e.solid = int(r.get_i64("event.solid"));
    e.event = r.get_string("event.event");
    e.value = r.get_f64("event.value");
    e.with = r.get_string("event.with");
    events_.push_back(std::move(e));
  }
}

}  // namespace refmap
