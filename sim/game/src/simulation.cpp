// SPDX-License-Identifier: MIT
#include "rewind/game/simulation.h"

#include <cstring>
#include <string>

#include "rewind/game/game_on.h"
#include "rewind/game/world_lane.h"
#include "rewind/sim/world3d.h"

namespace rwd::game {
namespace {

// Resync snapshots are "RWSIM" + version, then the sections below. A
// version bump is needed whenever the layout changes.
constexpr uint8_t kMagic[5] = {'R', 'W', 'S', 'I', 'M'};
constexpr uint8_t kVersion = 1;

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

uint32_t get_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

Status check_setup(const MatchSetup& setup) {
  if (setup.player_count < 1 || setup.player_count > kMaxPlayers) {
    return Status::Error(ErrorCode::kInvalidArgument, "player_count must be in [1, " +
                                                          std::to_string(kMaxPlayers) + "], got " +
                                                          std::to_string(setup.player_count));
  }
  return Status::Ok();
}

// The game `game_name` for a match of `setup`, or why there is none.
Result<std::unique_ptr<Game>> make_game(std::string_view game_name, const MatchSetup& setup) {
  if (Status status = check_setup(setup); !status.ok()) return status;
  std::unique_ptr<Game> game = make_builtin_game(game_name);
  if (!game) {
    std::string known;
    for (std::string_view name : builtin_game_names()) {
      if (!known.empty()) known += ", ";
      known += name;
    }
    return Status::Error(ErrorCode::kInvalidArgument,
                         "unknown game '" + std::string(game_name) + "' (known: " + known + ")");
  }
  return game;
}

}  // namespace

Result<std::unique_ptr<Simulation>> Simulation::create(std::string_view game_name,
                                                       const MatchSetup& setup) {
  Result<std::unique_ptr<Game>> game = make_game(game_name, setup);
  if (!game.ok()) return game.status();
  return create(std::move(*game), setup);
}

Result<std::unique_ptr<Simulation>> Simulation::create(std::unique_ptr<Game> game,
                                                       const MatchSetup& setup,
                                                       std::unique_ptr<Lane> lane) {
  if (game == nullptr) return Status::Error(ErrorCode::kInvalidArgument, "no game given");
  if (Status status = check_setup(setup); !status.ok()) return status;
  if (Status status = check_input_spec(game->input_spec()); !status.ok()) {
    return Status::Error(status.code(), "game '" + std::string(game->name()) +
                                            "' declares a bad input: " + status.message());
  }
  if (lane == nullptr) {
    lane = game->make_lane();
  } else if (!game->accepts_lane(*lane)) {
    // The game's calls cast the lane to its own world type without a check
    // (once per tick), so a lane of another type is refused here.
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game '" + std::string(game->name()) + "' does not run on the lane given");
  }
  std::unique_ptr<Simulation> sim(new Simulation(std::move(game), setup, std::move(lane)));
  if (Status status = sim->game_->build(sim->setup_, *sim->lane_, sim->game_state_); !status.ok()) {
    return Status::Error(status.code(), "game '" + std::string(sim->game_->name()) +
                                            "' could not build its match: " + status.message());
  }
  return sim;
}

Result<std::unique_ptr<Simulation>> Simulation::create(std::string_view game_name,
                                                       const MatchSetup& setup,
                                                       const sim::WorldConfig& world_config) {
  Result<std::unique_ptr<Game>> game = make_game(game_name, setup);
  if (!game.ok()) return game.status();
  if (dynamic_cast<const GameOn<sim::World3D>*>(game->get()) == nullptr) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game '" + std::string(game_name) + "' does not run the 3D lane");
  }
  if (Status status = sim::World3D::validate_config(world_config); !status.ok()) {
    return Status::Error(ErrorCode::kInvalidArgument, "world config: " + status.message());
  }
  return create(std::move(*game), setup, std::make_unique<WorldLane<sim::World3D>>(world_config));
}

SimSnapshot::SimSnapshot(const SimSnapshot& other)
    : world(other.world ? other.world->clone() : nullptr),
      game_state(other.game_state),
      tick(other.tick) {}

SimSnapshot& SimSnapshot::operator=(const SimSnapshot& other) {
  if (this != &other) *this = SimSnapshot(other);
  return *this;
}

Simulation::Simulation(std::unique_ptr<Game> game, const MatchSetup& setup,
                       std::unique_ptr<Lane> lane)
    : game_(std::move(game)), setup_(setup), lane_(std::move(lane)) {
  game_state_.assign(game_->state_size(), std::byte{0});
}

Status Simulation::step(std::span<const PlayerInput> inputs) {
  // The rules may rely on their spec: an input outside it never reaches
  // them, and the state stays as it was.
  const InputSpec& spec = game_->input_spec();
  for (size_t p = 0; p < inputs.size(); ++p) {
    if (Status bad = check_input(spec, inputs[p]); !bad.ok()) {
      return Status::Error(bad.code(), "game '" + std::string(game_->name()) + "', tick " +
                                           std::to_string(tick_) + ": player " + std::to_string(p) +
                                           ": " + bad.message());
    }
  }
  Status status = game_->apply_inputs(tick_, inputs, *lane_, game_state_);
  if (status.ok()) {
    lane_->step();
    status = game_->after_step(tick_, *lane_, game_state_);
  }
  if (!status.ok()) {
    return Status::Error(status.code(), "game '" + std::string(game_->name()) + "', tick " +
                                            std::to_string(tick_) + ": " + status.message());
  }
  ++tick_;
  return status;
}

void Simulation::save(SimSnapshot& out) const {
  if (!out.world) out.world = lane_->make_snapshot();
  lane_->save(*out.world);
  out.game_state = game_state_;
  out.tick = tick_;
}

void Simulation::restore(const SimSnapshot& in) {
  lane_->restore(*in.world);
  game_state_ = in.game_state;
  tick_ = in.tick;
}

uint64_t Simulation::checksum() const {
  rwd::StateHasher hasher;
  hasher.add_i32(tick_);
  lane_->hash(hasher);
  game_->hash_state(game_state_, hasher);
  return hasher.digest();
}

uint64_t Simulation::checksum_of(const SimSnapshot& snapshot) const {
  rwd::StateHasher hasher;
  hasher.add_i32(snapshot.tick);
  lane_->hash_snapshot(*snapshot.world, hasher);
  game_->hash_state(snapshot.game_state, hasher);
  return hasher.digest();
}

void Simulation::serialize(std::vector<uint8_t>& out) const {
  std::vector<uint8_t> world_bytes;
  lane_->serialize(world_bytes);
  out.clear();
  out.reserve(sizeof(kMagic) + 1 + 12 + game_state_.size() + world_bytes.size());
  for (uint8_t b : kMagic) out.push_back(b);
  out.push_back(kVersion);
  put_u32(out, static_cast<uint32_t>(tick_));
  put_u32(out, static_cast<uint32_t>(game_state_.size()));
  for (std::byte b : game_state_) out.push_back(static_cast<uint8_t>(b));
  put_u32(out, static_cast<uint32_t>(world_bytes.size()));
  out.insert(out.end(), world_bytes.begin(), world_bytes.end());
}

Status Simulation::deserialize(std::span<const uint8_t> bytes) {
  constexpr size_t kHeader = sizeof(kMagic) + 1 + 4 + 4;
  if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    return Status::Error(ErrorCode::kCorrupt, "simulation snapshot: bad magic or too short");
  }
  if (bytes[sizeof(kMagic)] != kVersion) {
    return Status::Error(ErrorCode::kCorrupt, "simulation snapshot: unsupported version " +
                                                  std::to_string(bytes[sizeof(kMagic)]));
  }
  const uint8_t* p = bytes.data() + sizeof(kMagic) + 1;
  const auto tick = static_cast<Tick>(get_u32(p));
  const uint32_t game_size = get_u32(p + 4);
  if (tick < 0) return Status::Error(ErrorCode::kCorrupt, "simulation snapshot: negative tick");
  if (game_size != game_state_.size()) {
    return Status::Error(ErrorCode::kCorrupt,
                         "simulation snapshot: game state is " + std::to_string(game_size) +
                             " bytes, this game uses " + std::to_string(game_state_.size()));
  }
  size_t offset = kHeader;
  if (bytes.size() - offset < size_t{game_size} + 4) {
    return Status::Error(ErrorCode::kCorrupt, "simulation snapshot: truncated game state");
  }
  std::span<const uint8_t> game_bytes = bytes.subspan(offset, game_size);
  if (Status status = game_->validate_state(setup_, std::as_bytes(game_bytes)); !status.ok()) {
    return status;
  }
  offset += game_size;
  const uint32_t world_size = get_u32(bytes.data() + offset);
  offset += 4;
  if (bytes.size() - offset != world_size) {
    return Status::Error(ErrorCode::kCorrupt, "simulation snapshot: world section is " +
                                                  std::to_string(bytes.size() - offset) +
                                                  " bytes, header says " +
                                                  std::to_string(world_size));
  }
  // The world validates its own section and stays untouched on error, so
  // nothing here changes until it has accepted the bytes.
  Status status = lane_->deserialize(bytes.subspan(offset, world_size));
  if (!status.ok()) return status;
  std::memcpy(game_state_.data(), game_bytes.data(), game_size);
  tick_ = tick;
  return Status::Ok();
}

}  // namespace rwd::game
