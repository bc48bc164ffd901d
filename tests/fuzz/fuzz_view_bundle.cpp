// SPDX-License-Identifier: MIT
// View bundles come from files a user hands the viewer (or a page fetches):
// the reader must refuse anything malformed with a message; whatever it
// accepts must re-encode to the same bytes, and a player made from it must
// step its first ticks and open its desync report (a client's state, as
// untrusted as the rest) without failing in any other way than a Status.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/viewer/replay_player.h"
#include "rewind/viewer/view_bundle.h"

int fuzz_view_bundle_one(const uint8_t* data, size_t size) {
  auto bundle = rwd::viewer::decode_view_bundle({data, size});
  if (!bundle.ok()) {
    if (bundle.status().message().empty()) std::abort();
    return 0;
  }
  // Re-encoding writes the newest version: the same bytes for one of
  // those, the same bundle (encoding alike twice) for an older one.
  const bool newest = size >= 12 && data[8] == rwd::viewer::kViewBundleVersion && data[9] == 0 &&
                      data[10] == 0 && data[11] == 0;
  std::vector<uint8_t> again;
  bool same = rwd::viewer::encode_view_bundle(*bundle, again).ok();
  if (same && newest) same = again.size() == size && std::memcmp(again.data(), data, size) == 0;
  if (same && !newest) {
    auto reread = rwd::viewer::decode_view_bundle(again);
    std::vector<uint8_t> twice;
    same = reread.ok() && rwd::viewer::encode_view_bundle(*reread, twice).ok() && twice == again;
  }
  if (!same) {
    std::fprintf(stderr, "fuzz_view_bundle: an accepted bundle does not re-encode\n");
    std::abort();
  }
  auto player = rwd::viewer::ReplayPlayer::create(std::move(*bundle), 2);
  if (!player.ok()) return 0;  // a game this build lacks, a setup it refuses
  for (int i = 0; i < 3 && (*player)->step(); ++i) {
  }
  (*player)->seek((*player)->start() + 1);
  (void)(*player)->open_desync();
  return 0;
}
