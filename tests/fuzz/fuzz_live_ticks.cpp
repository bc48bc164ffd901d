// SPDX-License-Identifier: MIT
// Live tick batches come from a server a browser polls: the reader must
// refuse anything malformed with a message; whatever it accepts must
// re-encode to the same bytes, and appending it to a player must either
// take it or refuse it with a Status, after which the player still steps.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/viewer/live_ticks.h"
#include "rewind/viewer/replay_player.h"

int fuzz_live_ticks_one(const uint8_t* data, size_t size) {
  auto batch = rwd::viewer::decode_live_ticks({data, size});
  if (!batch.ok()) {
    if (batch.status().message().empty()) std::abort();
    return 0;
  }
  std::vector<uint8_t> again;
  if (!rwd::viewer::encode_live_ticks(*batch, again).ok() || again.size() != size ||
      std::memcmp(again.data(), data, size) != 0) {
    std::fprintf(stderr, "fuzz_live_ticks: an accepted batch does not re-encode\n");
    std::abort();
  }
  rwd::viewer::ViewBundle bundle;
  bundle.game = "arena";
  bundle.setup = {2, 5};
  auto player = rwd::viewer::ReplayPlayer::create(std::move(bundle), 2, 3);
  if (!player.ok()) std::abort();
  const rwd::Tick before = (*player)->length();
  const rwd::Status appended = (*player)->append(*batch);
  if (!appended.ok() && (appended.message().empty() || (*player)->length() != before)) {
    std::fprintf(stderr, "fuzz_live_ticks: a refused batch changed the player\n");
    std::abort();
  }
  for (int i = 0; i < 4 && (*player)->step(); ++i) {
  }
  (*player)->seek(1);
  return 0;
}
