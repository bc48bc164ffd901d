// SPDX-License-Identifier: MIT
#pragma once
// Replay files and desync reports as a viewer loads them: a view bundle
// (rewind/viewer/view_bundle.h) holding the replay's game, setup, every
// tick's inputs and checksum, and optionally a client's desync report.
#include <span>
#include <string>

#include "rewind/core/status.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/viewer/view_bundle.h"

namespace rwd::replay {

/// What a conversion read besides the bundle.
struct ReplayViewInfo {
  ReadState file_state = ReadState::kReading;  ///< how reading the file ended
  std::string problem;  ///< why reading stopped early (a torn or corrupt record), if it did
};

/// Reads every tick record of `reader`'s valid prefix into a bundle, with
/// the replay's keyframes for the viewer to seek through. A file
/// that is torn or corrupt part way gives the ticks before the damage, and
/// `info` says where reading stopped. kInvalidArgument when the header's
/// game or player count cannot make a bundle.
Result<viewer::ViewBundle> view_bundle_from_replay(ReplayReader& reader, ReplayViewInfo* info);

/// A bundle from `path`: a view bundle as written before (it starts with
/// "RWDVIEW1"), or a replay file read as view_bundle_from_replay() does.
/// kIo when the file cannot be read, kCorrupt when it is neither.
Result<viewer::ViewBundle> load_view_bundle(const std::string& path, ReplayViewInfo* info);

/// Adds a client's desync report to `bundle`: the raw state the server
/// stored as DIR/desync_pP_tT_rR.bin (Simulation::serialize bytes) and
/// the headline of its .txt beside it (the first line; empty when the
/// file is missing). The player and tick come from the file name.
/// kInvalidArgument for a name of another form or a tick past the
/// bundle's ticks, kIo when the .bin cannot be read; `bundle` is unchanged
/// on error.
Status attach_desync_report(viewer::ViewBundle& bundle, const std::string& bin_path);

}  // namespace rwd::replay
