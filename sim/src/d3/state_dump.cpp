// SPDX-License-Identifier: MIT
// The readable dump: every persisted field by its schema name
// (state_schema.h), one per line, in the canonical order, for desync
// forensics and debugging. Floats print with nine significant digits, so
// the text names every bit a checksum sees.
#include <cinttypes>
#include <cstdio>
#include <string>

#include "d3/state_schema.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

class TextIo {
 public:
  TextIo(std::string& out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}
  void u8(const char* name, uint8_t v) { line(name, std::to_string(v)); }
  void flag(const char* name, uint8_t v) { line(name, std::to_string(v)); }
  void boolean(const char* name, bool v) { line(name, v ? "1" : "0"); }
  template <class E>
  void enumeration(const char* name, E v, E) {
    line(name, std::to_string(static_cast<uint32_t>(v)));
  }
  void count(const char* name, uint8_t v, uint8_t) { line(name, std::to_string(v)); }
  void event_mask(const char* name, EventMask v) { line(name, std::to_string(v)); }
  void u32(const char* name, uint32_t v) { line(name, std::to_string(v)); }
  void i32(const char* name, int32_t v) { line(name, std::to_string(v)); }
  void u64(const char* name, uint64_t v) { line(name, std::to_string(v)); }
  void f32(const char* name, float v) { line(name, number(v)); }
  void vec3(const char* name, Vec3 v) {
    line(name, number(v.x) + " " + number(v.y) + " " + number(v.z));
  }
  void quat(const char* name, Quat q) {
    line(name, number(q.x) + " " + number(q.y) + " " + number(q.z) + " " + number(q.w));
  }

 private:
  static std::string number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.9g", static_cast<double>(v));
    return buf;
  }
  void line(const char* name, const std::string& value) {
    out_ += prefix_;
    out_ += name;
    out_ += " = ";
    out_ += value;
    out_ += '\n';
  }
  std::string& out_;
  std::string prefix_;
};

}  // namespace

void World3D::dump_state(std::string& out) const {
  out.clear();
  TextIo config(out, "config.");
  d3::visit_config(config, state_.config);
  out += "step_count = " + std::to_string(state_.step_count) + "\n";
  for (uint32_t i = 0; i < state_.infos.size(); ++i) {
    const BodyInfo& b = state_.infos[i];
    const std::string prefix = "body[" + std::to_string(i) + "].";
    out += prefix + "generation = " + std::to_string(b.generation) + "\n";
    out += prefix + "alive = " + std::to_string(b.alive) + "\n";
    if (b.alive == 0) continue;
    TextIo io(out, prefix);
    d3::visit_body(io, b, state_.sims[i]);
  }
  for (size_t k = 0; k < state_.contacts.size(); ++k) {
    TextIo io(out, "contact[" + std::to_string(k) + "].");
    d3::visit_contact(io, state_.contacts[k]);
  }
  for (size_t k = 0; k < state_.joints.size(); ++k) {
    const JointRecord& j = state_.joints[k];
    const std::string prefix = "joint[" + std::to_string(k) + "].";
    out += prefix + "generation = " + std::to_string(j.generation) + "\n";
    out += prefix + "alive = " + std::to_string(j.alive) + "\n";
    if (j.alive == 0) continue;
    TextIo io(out, prefix);
    d3::visit_joint(io, j);
  }
  out += "last_query_ticket = " + std::to_string(state_.last_query_ticket) + "\n";
  for (size_t k = 0; k < state_.queries.size(); ++k) {
    TextIo io(out, "query[" + std::to_string(k) + "].");
    d3::visit_query(io, state_.queries[k]);
  }
}

}  // namespace rwd::sim
