// SPDX-License-Identifier: MIT
#include "d3/contact_cache_steady.h"

#include <tuple>

namespace rwd::sim::d3 {
namespace {

// A record's place in the cache order: (index_a, index_b, part).
std::tuple<uint32_t, uint32_t, uint8_t> order_key(const ContactRecord& r) {
  return {r.index_a, r.index_b, r.part};
}

}  // namespace

bool steady_cache_usable(const WorldState& state, const WorldScratch& scratch) {
  if (scratch.steady_serial == 0 || scratch.steady_serial != scratch.edit_serial) return false;
  // Worth it only when most of the cache rests: the path copies the
  // evaluated records twice, where the full merge swaps the whole cache.
  if (scratch.steady_records.size() * 4 > state.contacts.size()) return false;
  if (!scratch.steady_records.empty() && scratch.steady_records.back() >= state.contacts.size()) {
    return false;
  }
  // Both lists ascending: every body awake now was awake then.
  const std::vector<uint32_t>& then = scratch.steady_active;
  size_t j = 0;
  for (const uint32_t i : scratch.active) {
    while (j < then.size() && then[j] < i) ++j;
    if (j == then.size() || then[j] != i) return false;
  }
  return true;
}

void steady_old_records(const WorldState& state, WorldScratch& scratch) {
  scratch.steady_view = scratch.steady_records;
  std::vector<ContactRecord>& old = scratch.other_contacts;
  old.clear();
  for (const uint32_t k : scratch.steady_view) old.push_back(state.contacts[k]);
}

void place_steady_records(WorldState& state, WorldScratch& scratch) {
  const std::vector<ContactRecord>& fresh = scratch.steady_new;
  const std::vector<uint32_t>& view = scratch.steady_view;
  std::vector<uint32_t>& evaluated = scratch.evaluated_records;
  bool same = fresh.size() == view.size();
  for (size_t j = 0; same && j < fresh.size(); ++j) {
    same = order_key(fresh[j]) == order_key(state.contacts[view[j]]);
  }
  if (same) {
    for (size_t j = 0; j < fresh.size(); ++j) {
      state.contacts[view[j]] = fresh[j];
      scratch.geometry[view[j]] = scratch.steady_geometry[j];
    }
    for (uint32_t& k : evaluated) k = view[k];
    scratch.contacts_in_place = true;
    return;
  }
  // The keys moved (a pair came or went): the carried records and this
  // step's, merged in cache order. Their keys never meet: a carried
  // record's bodies both rest, and this step's records each have an awake
  // body or were last step's evaluated ones.
  std::vector<ContactRecord>& out = scratch.other_contacts;
  out.clear();
  const std::vector<ContactRecord>& old = state.contacts;
  std::vector<ContactGeometry>& geometry = scratch.geometry;
  if (geometry.size() < old.size() + fresh.size()) geometry.resize(old.size() + fresh.size());
  std::vector<uint32_t>& placed = scratch.steady_placed;
  placed.resize(fresh.size());
  size_t v = 0;
  size_t j = 0;
  for (uint32_t k = 0; k <= old.size(); ++k) {
    const bool carried = k < old.size() && !(v < view.size() && view[v] == k);
    if (k < old.size() && !carried) {
      ++v;
      continue;
    }
    while (j < fresh.size() && (k == old.size() || order_key(fresh[j]) < order_key(old[k]))) {
      placed[j] = static_cast<uint32_t>(out.size());
      geometry[out.size()] = scratch.steady_geometry[j];
      out.push_back(fresh[j++]);
    }
    if (k == old.size()) break;
    geometry[out.size()].valid = 0;
    out.push_back(old[k]);
  }
  for (uint32_t& k : evaluated) k = placed[k];
  state.contacts.swap(out);  // other_contacts: last step's whole cache
}

void remember_steady(WorldScratch& scratch) {
  scratch.steady_serial = scratch.edit_serial;
  scratch.steady_active = scratch.active;
  scratch.steady_records = scratch.evaluated_records;
}

void unfold_steady(const WorldState& state, WorldScratch& scratch) {
  if (!scratch.contacts_in_place) return;
  // steady_new is spent by now (placed in the cache): its storage holds the
  // copy.
  std::vector<ContactRecord>& whole = scratch.steady_new;
  whole = state.contacts;
  for (size_t j = 0; j < scratch.steady_view.size(); ++j) {
    whole[scratch.steady_view[j]] = scratch.other_contacts[j];
  }
  scratch.other_contacts.swap(whole);
  scratch.contacts_in_place = false;
}

}  // namespace rwd::sim::d3
