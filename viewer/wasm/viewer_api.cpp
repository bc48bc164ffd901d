// SPDX-License-Identifier: MIT
// The browser viewer's entry points: a C interface over ReplayPlayer that
// JavaScript calls through Emscripten (viewer/web/viewer.js). One player
// per module instance, and for 3D games a cosmetic world of debris thrown
// from hard impacts (rewind/sim/cosmetic_world.h): drawn, never part of
// the match. Strings returned stay valid until the next call
// that returns one; buffers until the next rv_draw. Every call is safe
// before a bundle is loaded (it answers zero, empty or -1).
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rewind/game/world_lane.h"
#include "rewind/sim/cosmetic_world.h"
#include "rewind/sim2d/world2d.h"
#include "rewind/viewer/replay_player.h"

#if defined(__EMSCRIPTEN__)
#include <emscripten/emscripten.h>
#define RV_EXPORT extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define RV_EXPORT extern "C"
#endif

namespace {

using rwd::viewer::ReplayPlayer;

struct ViewerState {
  std::unique_ptr<ReplayPlayer> player;
  /// Debris for the eye (3D games): props thrown from hard impacts, on
  /// proxies of the match's bodies; never part of the match.
  std::unique_ptr<rwd::sim::CosmeticWorld> debris;
  uint32_t debris_seed = 1;
  std::string error;
  std::string text;  ///< the last string handed out
  rwd::DebugDrawBuffers draw;
  std::optional<rwd::viewer::DesyncView> desync;
  /// What the last live batch said of the match.
  rwd::Tick newest_final = rwd::kNoTick;
  bool ended = false;
};

ViewerState& state() {
  static ViewerState s;
  return s;
}

const char* hand_out(std::string text) {
  state().text = std::move(text);
  return state().text.c_str();
}

std::string hex64(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

const rwd::sim::World3D* world3d() {
  const ViewerState& s = state();
  return s.player ? rwd::game::world_of<rwd::sim::World3D>(s.player->simulation().lane()) : nullptr;
}

/// The debris layer follows one tick of the match: proxies to the new
/// poses, a few props thrown from each hard impact of the tick, one step.
void debris_after_step() {
  ViewerState& s = state();
  const rwd::sim::World3D* world = world3d();
  if (!s.debris || world == nullptr) return;
  s.debris->sync(*world);
  uint32_t impacts = 0;
  for (const rwd::sim::ContactEvent& e : world->events()) {
    if (e.type != rwd::sim::ContactEventType::kEnter || e.sensor || e.impulse < 40.0f) continue;
    if (++impacts > 4) break;
    for (int k = 0; k < 4; ++k) {
      auto next = [&s] {  // a small LCG: debris needs variety, not determinism
        s.debris_seed = s.debris_seed * 1664525u + 1013904223u;
        return static_cast<float>(s.debris_seed >> 8) / 16777216.0f - 0.5f;
      };
      rwd::sim::BodyDef def;
      const float half = 0.04f + 0.04f * (next() + 0.5f);
      def.shape = rwd::sim::Shape::make_box({half, half, half});
      def.position = e.point + e.normal * 0.15f +
                     rwd::sim::Vec3{next() * 0.3f, 0.1f + (next() + 0.5f) * 0.2f, next() * 0.3f};
      def.linear_velocity =
          rwd::sim::Vec3{next() * 3.0f, 2.0f + (next() + 0.5f) * 2.0f, next() * 3.0f};
      def.angular_velocity = {next() * 10.0f, next() * 10.0f, next() * 10.0f};
      def.density = 500.0f;
      (void)s.debris->add_prop(def);
    }
  }
  s.debris->step();
}

/// After a jump (a seek), the debris starts over where the match is.
void debris_reset() {
  ViewerState& s = state();
  if (!s.debris) return;
  s.debris->clear_props();
  s.debris->teleport_next_sync();
  if (const rwd::sim::World3D* world = world3d()) s.debris->sync(*world);
}

/// rv_draw's flag bits.
enum : uint32_t {
  kDrawShapes = 1u << 0,
  kDrawSolids = 1u << 1,
  kDrawContacts = 1u << 2,
  kDrawNormals = 1u << 3,
  kDrawJoints = 1u << 4,
  kDrawBounds = 1u << 5,
  kDrawCenters = 1u << 6,
  kDrawStatics = 1u << 7,
  kDrawDebris = 1u << 8,
};

}  // namespace

/// Loads a view bundle from `size` bytes at `bytes` (copied), keeping a
/// snapshot every `keyframe_every` ticks, at most `max_keyframes` of them
/// (0: all; a live viewer bounds them). 0 on success; otherwise the error
/// code and rv_error() says why, and any player loaded before stays.
RV_EXPORT int rv_load(const uint8_t* bytes, uint32_t size, uint32_t keyframe_every,
                      uint32_t max_keyframes) {
  ViewerState& s = state();
  auto bundle = rwd::viewer::decode_view_bundle(std::span<const uint8_t>(bytes, size));
  if (!bundle.ok()) {
    s.error = bundle.status().message();
    return static_cast<int>(bundle.status().code());
  }
  auto player = ReplayPlayer::create(std::move(*bundle), keyframe_every, max_keyframes);
  if (!player.ok()) {
    s.error = player.status().message();
    return static_cast<int>(player.status().code());
  }
  s.player = std::move(*player);
  s.newest_final = rwd::kNoTick;
  s.ended = false;
  s.desync.reset();
  s.error.clear();
  s.debris.reset();
  if (const rwd::sim::World3D* world = world3d()) {
    rwd::sim::CosmeticConfig config;
    config.world = world->config();
    config.max_props = 200;
    config.prop_lifetime_s = 4.0f;
    auto debris = rwd::sim::CosmeticWorld::create(config, world->shared_geometry());
    if (debris.ok()) s.debris = std::move(*debris);
    debris_reset();
  }
  return 0;
}

/// Appends a live tick batch (`size` bytes at `bytes`, as a server's
/// /live/<match>/ticks answers) to the loaded match. 0 on success;
/// otherwise the error code, rv_error() says why and nothing changed.
RV_EXPORT int rv_append(const uint8_t* bytes, uint32_t size) {
  ViewerState& s = state();
  if (!s.player) {
    s.error = "no match loaded";
    return static_cast<int>(rwd::ErrorCode::kNotFound);
  }
  auto batch = rwd::viewer::decode_live_ticks(std::span<const uint8_t>(bytes, size));
  if (!batch.ok()) {
    s.error = batch.status().message();
    return static_cast<int>(batch.status().code());
  }
  if (rwd::Status appended = s.player->append(*batch); !appended.ok()) {
    s.error = appended.message();
    return static_cast<int>(appended.code());
  }
  s.newest_final = batch->newest_final;
  s.ended = batch->ended;
  s.error.clear();
  return 0;
}

/// The newest final tick of the live match as of the last batch (-1:
/// none, or not live).
RV_EXPORT int rv_live_newest_final() {
  return state().newest_final;
}

/// 1 once a live batch said the match is over.
RV_EXPORT int rv_live_ended() {
  return state().ended ? 1 : 0;
}

/// The first position: 0, or the tick a live viewer joined at.
RV_EXPORT int rv_start() {
  return state().player ? state().player->start() : -1;
}

RV_EXPORT const char* rv_error() {
  return state().error.c_str();
}

RV_EXPORT int rv_loaded() {
  return state().player ? 1 : 0;
}

RV_EXPORT const char* rv_game() {
  return hand_out(state().player ? state().player->bundle().game : "");
}

RV_EXPORT int rv_players() {
  return state().player ? static_cast<int>(state().player->bundle().setup.player_count) : 0;
}

RV_EXPORT const char* rv_player_name(int player) {
  const ViewerState& s = state();
  if (!s.player || player < 0 ||
      static_cast<size_t>(player) >= s.player->bundle().player_names.size()) {
    return hand_out("");
  }
  return hand_out(s.player->bundle().player_names[static_cast<size_t>(player)]);
}

RV_EXPORT int rv_tick_rate() {
  return state().player ? static_cast<int>(state().player->bundle().tick_rate_hz) : 0;
}

/// 1 when the recording engine, rules and config are this build's.
RV_EXPORT int rv_identity_matches() {
  return state().player && state().player->bundle().identity_matches ? 1 : 0;
}

RV_EXPORT const char* rv_identity_note() {
  return hand_out(state().player ? state().player->bundle().identity_note : "");
}

/// 1 when the game runs on the 2D lane (the viewer then looks at the x-y
/// plane from +z).
RV_EXPORT int rv_is_2d() {
  const ViewerState& s = state();
  if (!s.player) return 0;
  return rwd::game::world_of<rwd::sim2d::World2D>(s.player->simulation().lane()) != nullptr ? 1 : 0;
}

RV_EXPORT int rv_position() {
  return state().player ? state().player->position() : -1;
}

RV_EXPORT int rv_length() {
  return state().player ? state().player->length() : -1;
}

/// One tick forward; 0 at the end.
RV_EXPORT int rv_step() {
  if (!state().player || !state().player->step()) return 0;
  debris_after_step();
  return 1;
}

RV_EXPORT void rv_seek(int position) {
  ViewerState& s = state();
  if (!s.player) return;
  if (position == s.player->position() + 1) {
    rv_step();
    return;
  }
  s.player->seek(position);
  debris_reset();
}

/// Re-simulates up to `max_steps` ticks from the start apart from the view
/// (ReplayPlayer::verify), so ticks a seek jumped over get their checks;
/// the position verified through.
RV_EXPORT int rv_verify(uint32_t max_steps) {
  return state().player ? state().player->verify(max_steps) : -1;
}

/// Debris props alive (3D games; 0 otherwise).
RV_EXPORT int rv_debris_count() {
  return state().debris ? static_cast<int>(state().debris->prop_count()) : 0;
}

/// The state's checksum, 16 hex digits.
RV_EXPORT const char* rv_checksum() {
  return hand_out(state().player ? hex64(state().player->checksum()) : "");
}

/// The recorded checksum at this position, or "" at position 0.
RV_EXPORT const char* rv_recorded_checksum() {
  const ViewerState& s = state();
  if (!s.player) return hand_out("");
  const auto recorded = s.player->recorded_checksum();
  return hand_out(recorded ? hex64(*recorded) : "");
}

/// 0 unchecked, 1 matched, 2 differed (TickCheck) for `position`.
RV_EXPORT int rv_check(int position) {
  return state().player ? static_cast<int>(state().player->check(position)) : 0;
}

RV_EXPORT int rv_first_mismatch() {
  const ViewerState& s = state();
  if (!s.player || !s.player->first_mismatch()) return -1;
  return *s.player->first_mismatch();
}

/// Bodies, awake bodies, touching pairs, contact points, joints
/// (index 0 to 4), as of the last step.
RV_EXPORT int rv_stat(int which) {
  const ViewerState& s = state();
  if (!s.player) return 0;
  const rwd::WorldViewStats v = s.player->stats();
  const uint32_t values[] = {v.bodies, v.awake_bodies, v.touching_pairs, v.contact_points,
                             v.joints};
  return which >= 0 && which < 5 ? static_cast<int>(values[which]) : 0;
}

/// Fills the draw buffers (flags: the kDraw* bits above) with
/// `highlight_count` body indices at `highlight` drawn in the highlight
/// colour. Lines and triangles are 16-byte vertices (x, y, z float32,
/// colour 0xRRGGBBAA), points 20 bytes (the same and a size in pixels).
RV_EXPORT void rv_draw(uint32_t flags, const uint32_t* highlight, uint32_t highlight_count) {
  ViewerState& s = state();
  s.draw.clear();
  if (!s.player) return;
  rwd::DebugDrawOptions o;
  o.shapes = (flags & kDrawShapes) != 0;
  o.solid_shapes = (flags & kDrawSolids) != 0;
  o.contacts = (flags & kDrawContacts) != 0;
  o.contact_normals = (flags & kDrawNormals) != 0;
  o.joints = (flags & kDrawJoints) != 0;
  o.bounds = (flags & kDrawBounds) != 0;
  o.centers_of_mass = (flags & kDrawCenters) != 0;
  o.static_shapes = (flags & kDrawStatics) != 0;
  o.highlight_bodies = std::span<const uint32_t>(highlight, highlight_count);
  s.player->draw(o, s.draw);
  if (s.debris && (flags & kDrawDebris) != 0) s.debris->draw_props(o, 0xC8A06EFFu, s.draw);
}

RV_EXPORT const void* rv_lines() {
  return state().draw.lines.data();
}
RV_EXPORT uint32_t rv_line_vertices() {
  return static_cast<uint32_t>(state().draw.lines.size());
}
RV_EXPORT const void* rv_triangles() {
  return state().draw.triangles.data();
}
RV_EXPORT uint32_t rv_triangle_vertices() {
  return static_cast<uint32_t>(state().draw.triangles.size());
}
RV_EXPORT const void* rv_points() {
  return state().draw.points.data();
}
RV_EXPORT uint32_t rv_point_count() {
  return static_cast<uint32_t>(state().draw.points.size());
}

/// Where body `index` is now (3 floats, m; z = 0 in 2D), or null when no
/// live body is there. Valid until the next call.
RV_EXPORT const float* rv_body_center(int index) {
  static float at[3];
  const ViewerState& s = state();
  if (!s.player || index < 0) return nullptr;
  const auto c = s.player->body_center(static_cast<uint32_t>(index));
  if (!c) return nullptr;
  for (int k = 0; k < 3; ++k) at[k] = static_cast<float>((*c)[static_cast<size_t>(k)]);
  return at;
}

/// 1 when the bundle holds a desync report.
RV_EXPORT int rv_has_desync() {
  return state().player && state().player->bundle().desync ? 1 : 0;
}

RV_EXPORT const char* rv_desync_headline() {
  const ViewerState& s = state();
  if (!s.player || !s.player->bundle().desync) return hand_out("");
  return hand_out(s.player->bundle().desync->headline);
}

/// Seeks to the desync and compares the client's state there: the number
/// of differing fields, or -1 (rv_error() says why).
RV_EXPORT int rv_open_desync() {
  ViewerState& s = state();
  if (!s.player) return -1;
  auto view = s.player->open_desync();
  if (!view.ok()) {
    s.error = view.status().message();
    return -1;
  }
  s.desync = std::move(*view);
  return static_cast<int>(s.desync->differences.size());
}

RV_EXPORT int rv_desync_position() {
  return state().desync ? state().desync->position : -1;
}

RV_EXPORT const char* rv_desync_client_checksum() {
  return hand_out(state().desync ? hex64(state().desync->client_checksum) : "");
}

/// The bodies the desync names (ascending): count, then each by index.
RV_EXPORT int rv_desync_body_count() {
  return state().desync ? static_cast<int>(state().desync->bodies.size()) : 0;
}
RV_EXPORT const uint32_t* rv_desync_bodies() {
  return state().desync ? state().desync->bodies.data() : nullptr;
}

/// Field difference i: its body, its name, the replay's ("expected") and
/// the client's ("actual") value.
RV_EXPORT int rv_desync_field_body(int i) {
  const ViewerState& s = state();
  if (!s.desync || i < 0 || static_cast<size_t>(i) >= s.desync->differences.size()) return -1;
  return static_cast<int>(s.desync->differences[static_cast<size_t>(i)].body_index);
}
RV_EXPORT const char* rv_desync_field_name(int i) {
  const ViewerState& s = state();
  if (!s.desync || i < 0 || static_cast<size_t>(i) >= s.desync->differences.size()) {
    return hand_out("");
  }
  return hand_out(s.desync->differences[static_cast<size_t>(i)].field);
}
RV_EXPORT double rv_desync_field_expected(int i) {
  const ViewerState& s = state();
  if (!s.desync || i < 0 || static_cast<size_t>(i) >= s.desync->differences.size()) return 0.0;
  return s.desync->differences[static_cast<size_t>(i)].expected;
}
RV_EXPORT double rv_desync_field_actual(int i) {
  const ViewerState& s = state();
  if (!s.desync || i < 0 || static_cast<size_t>(i) >= s.desync->differences.size()) return 0.0;
  return s.desync->differences[static_cast<size_t>(i)].actual;
}
