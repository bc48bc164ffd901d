// SPDX-License-Identifier: MIT
// Spectating a running match from the server that serves the page
// (rewind-server --live-bind): the viewer starts from the newest state the
// server publishes (GET live/<match>/start, a view bundle), polls the
// final ticks after the last one it has (GET live/<match>/ticks?from=T,
// a live tick batch) and re-simulates them itself, checking each tick's
// checksum against the server's as for a replay. It follows the newest
// tick; pausing, stepping or scrubbing stops following until "Follow
// live". A viewer that fell behind what the server holds (a sleeping tab)
// starts over from the newest state.
const $ = (id) => document.getElementById(id);

/** Polls per second while the match runs. */
const POLL_MS = 100;
/** Failed polls in a row (one a second) before the viewer gives up. */
const MAX_FAILURES = 30;

export class LiveLink {
  constructor(viewer, match) {
    this.viewer = viewer;
    this.match = match;
    this.base = `live/${encodeURIComponent(match)}`;
    this.following = true;
    this.polls = 0;
    this.restarts = 0;
    this.failures = 0;
    this.newestFinal = -1;
    this.ended = false;
    this.gone = null;  // why polling stopped
  }

  async begin() {
    await this.load();
    $('live').hidden = false;
    $('live-follow').onclick = () => this.followAgain();
    this.schedule(0);
  }

  async load() {
    const response = await fetch(`${this.base}/start`, { cache: 'no-store' });
    if (!response.ok) {
      throw new Error(`cannot spectate '${this.match}': ${response.status} ` +
        (await response.text()).trim());
    }
    // A snapshot every 5 s at 60 Hz, at most 24 of them: scrubbing back two
    // minutes stays quick and memory stays flat over a long match.
    this.viewer.loadBytes(new Uint8Array(await response.arrayBuffer()), 300, 24);
  }

  schedule(ms) {
    setTimeout(() => this.poll(), ms);
  }

  async poll() {
    const viewer = this.viewer;
    const m = viewer.mod;
    try {
      const response = await fetch(`${this.base}/ticks?from=${m._rv_length()}`, { cache: 'no-store' });
      if (response.status === 410) {
        ++this.restarts;
        await this.load();
        this.following = true;
      } else if (!response.ok) {
        this.stop(`the server no longer serves '${this.match}' (${response.status})`);
        return;
      } else {
        const bytes = new Uint8Array(await response.arrayBuffer());
        const rc = viewer.withBytes(bytes, (ptr, n) => m._rv_append(ptr, n));
        if (rc !== 0) throw new Error('a batch was refused: ' + viewer.str(m._rv_error()));
        ++this.polls;
        this.newestFinal = m._rv_live_newest_final();
        this.ended = m._rv_live_ended() === 1;
      }
      this.failures = 0;
      viewer.showNames();
      viewer.showRange();
      viewer.dirty = true;
      if (this.ended && m._rv_length() > this.newestFinal) {
        this.stop('the match is over');
        return;
      }
    } catch (e) {
      if (++this.failures >= MAX_FAILURES) {
        this.stop(`the server is unreachable: ${e.message || e}`);
        return;
      }
    }
    this.schedule(this.failures > 0 ? 1000 : POLL_MS);
  }

  stop(why) {
    this.gone = why;
    this.viewer.dirty = true;
  }

  followAgain() {
    this.viewer.setPlaying(false);
    this.following = true;
  }

  /** Ticks between the newest final tick and the one shown. */
  lag() {
    return Math.max(0, this.newestFinal - (this.viewer.mod._rv_position() - 1));
  }

  panel() {
    const state = this.gone
      ? `${this.gone} · final tick ${this.newestFinal}`
      : `● live · final tick ${this.newestFinal} · ${this.lag()} ticks behind` +
        (this.following ? '' : ' (paused)');
    $('live-state').textContent = state;
    $('live-state').className = this.gone ? '' : 'on-air';
    $('live-follow').disabled = this.following;
  }

  /** What the page API's live() reports. */
  report() {
    return { match: this.match, following: this.following, newestFinal: this.newestFinal,
      ended: this.ended, polls: this.polls, restarts: this.restarts, failures: this.failures,
      gone: this.gone, lag: this.lag() };
  }
}
