// SPDX-License-Identifier: MIT
// Rewind's client SDK for browser players: the native client (prediction,
// rollback, final-tick checksums, desync reports, secure packets) compiled
// to WebAssembly, driven over a WebSocket to rewind-server --websocket.
//
//   import { loadRewind } from "./rewind-client.js";
//   const rewind = await loadRewind();
//   const client = rewind.connect({
//     url: "wss://game.example.com:7800/matches/duel-7",
//     token: tokenFromYourBackend,          // hex string or Uint8Array
//     game: "crates",
//   });
//   client.on("matchStarted", () => ...);
//   client.on("desync", (e) => console.warn(e));
//   client.setInput({ axis_x: 100, axis_y: 0, buttons: 1 });  // by the game's field names
//
// The client steps its ticks on a timer of its own (every 4 ms) and on every
// message, so a game reads state whenever it draws: client.status(),
// client.draw(). Types: rewind-client.d.ts.
import RewindClientModule from "./rewind_client.js";

const EVENT_TYPES = [
  "joined", "matchStarted", "finalTick", "desync", "resynced", "matchEnded", "rejected",
  "disconnected", "resyncRefused",
];

// Bytes from a hex string (a connect token as rewind-token mint prints it).
function bytesOf(token) {
  if (token === undefined || token === null) return new Uint8Array(0);
  if (token instanceof Uint8Array) return token;
  const hex = String(token).trim();
  if (hex.length % 2 !== 0 || /[^0-9a-fA-F]/.test(hex)) {
    throw new Error("token: expected hex digits or a Uint8Array");
  }
  const out = new Uint8Array(hex.length / 2);
  for (let i = 0; i < out.length; ++i) out[i] = parseInt(hex.substr(2 * i, 2), 16);
  return out;
}

// A small seeded generator for the simulated network faults: the same seed
// drops and delays the same datagrams.
function mulberry32(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Latency, jitter and loss on one direction, for tests (faults option).
class FaultyPath {
  constructor(faults, seed, deliver) {
    this.faults = faults;
    this.random = mulberry32(seed);
    this.deliver = deliver;
  }
  send(bytes) {
    const f = this.faults;
    const drop = this.random() < (f.loss || 0);
    const jitter = (this.random() * 2 - 1) * (f.jitterMs || 0);
    if (drop) return;
    const delay = Math.max(0, (f.latencyMs || 0) + jitter);
    if (delay === 0) this.deliver(bytes);
    else setTimeout(() => this.deliver(bytes), delay);
  }
}

class Rewind {
  constructor(module) {
    this.module = module;
    this.specs = new Map();
  }

  /** The input a game takes: { name, size, fields: [{ name, type, offset, min, max }] }. */
  inputSpec(game) {
    if (!this.specs.has(game)) {
      const json = this.#call("rc_input_spec", "string", ["string"], [game]);
      if (json === "") throw new Error(this.#error());
      this.specs.set(game, JSON.parse(json));
    }
    return this.specs.get(game);
  }

  /**
   * Runs `game`'s simulation for a while before a match, in slices that keep
   * the page responsive, so the browser has optimized the step's code by the
   * time a match needs it (until then, re-simulating after a late input runs
   * several times slower and can stall the page for a second or more).
   * Resolves once `ticks` ticks were stepped; call it while the player is in
   * a menu, before connect().
   */
  async warmUp(game, { ticks = 600, players = 4, sliceTicks = 8 } = {}) {
    let stepped = 0;
    while (stepped < ticks) {
      const n = Math.min(sliceTicks, ticks - stepped);
      if (this.#call("rc_warm_up", "number", ["string", "number", "number"], [game, players, n]) < 0) {
        throw new Error(this.#error());
      }
      stepped += n;
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
  }

  /** Opens a client and starts joining; see rewind-client.d.ts for the options. */
  connect(options) {
    return new RewindClient(this, options);
  }

  #call(name, returns, types, args) {
    return this.module.ccall(name, returns, types, args);
  }
  #error() {
    return this.module.ccall("rc_error", "string", [], []);
  }
}

class RewindClient {
  constructor(rewind, options) {
    if (!options || !options.url || !options.game) {
      throw new Error("connect: url and game are required");
    }
    const m = rewind.module;
    this.module = m;
    this.spec = rewind.inputSpec(options.game);
    this.listeners = new Map();
    this.closed = false;
    this.bytesIn = 0;
    this.bytesOut = 0;
    const token = bytesOf(options.token);
    const nonce = new Uint32Array(2);
    crypto.getRandomValues(nonce);
    const tokenPtr = m._malloc(Math.max(1, token.length));
    m.HEAPU8.set(token, tokenPtr);
    this.handle = m.ccall(
      "rc_create", "number",
      ["string", "string", "number", "number", "number", "number", "number", "number"],
      [options.game, options.name || "browser", tokenPtr, token.length, options.spectator ? 1 : 0,
       options.snapshotTicks || 0, nonce[0], nonce[1]]);
    m._free(tokenPtr);
    if (this.handle < 0) throw new Error(m.ccall("rc_error", "string", [], []));
    this.sizePtr = m._malloc(24);  // out parameters: a size, and rc_draw's five

    const faults = options.faults;
    const seed = faults && faults.seed !== undefined ? faults.seed : 1;
    const send = (bytes) => {
      if (this.socket.readyState === WebSocket.OPEN) {
        this.bytesOut += bytes.length;
        this.socket.send(bytes);
      }
    };
    const receive = (bytes) => this.#receive(bytes);
    this.outgoing = faults ? new FaultyPath(faults, seed, send) : { send };
    this.incoming = faults ? new FaultyPath(faults, seed ^ 0x9e3779b9, receive) : { send: receive };

    this.socket = new WebSocket(options.url, "rewind");
    this.socket.binaryType = "arraybuffer";
    this.socket.onopen = () => {
      m.ccall("rc_connect", null, ["number", "number"], [this.handle, performance.now()]);
      this.#pump();
    };
    this.socket.onmessage = (message) => {
      const bytes = new Uint8Array(message.data);
      this.bytesIn += bytes.length;
      this.incoming.send(bytes);
    };
    this.socket.onclose = () => {
      if (!this.closed) this.#emit({ type: "socketClosed", reason: "the WebSocket closed" });
    };
    this.timer = setInterval(() => this.#pump(), options.updateEveryMs || 4);
  }

  /** Calls `listener(event)` for every event of `type` ("*" for all). */
  on(type, listener) {
    if (type !== "*" && type !== "socketClosed" && !EVENT_TYPES.includes(type)) {
      throw new Error(`on: no event '${type}' (one of ${EVENT_TYPES.join(", ")}, socketClosed, *)`);
    }
    if (!this.listeners.has(type)) this.listeners.set(type, []);
    this.listeners.get(type).push(listener);
    return this;
  }

  /**
   * Our input from the next tick on: an object of the game's field names
   * (missing fields are 0) or the raw bytes. Throws when the game's spec
   * refuses it; the held input stays.
   */
  setInput(input) {
    const bytes = input instanceof Uint8Array ? input : this.#encode(input);
    const m = this.module;
    const ptr = m._malloc(Math.max(1, bytes.length));
    m.HEAPU8.set(bytes, ptr);
    const result = m.ccall("rc_set_input", "number", ["number", "number", "number"],
                           [this.handle, ptr, bytes.length]);
    m._free(ptr);
    if (result !== 0) throw new Error(m.ccall("rc_error", "string", [], []));
  }

  /** Where the client is: phase, player, tick, checksum and the running figures. */
  status() {
    const json = this.module.ccall("rc_status", "string", ["number"], [this.handle]);
    if (json === "") return null;
    const status = JSON.parse(json);
    status.bytesIn = this.bytesIn;
    status.bytesOut = this.bytesOut;
    return status;
  }

  /**
   * The predicted present as line and triangle vertices (x, y, z float32 and
   * a colour, 16 bytes each), copied out: { lines, triangles } Float32Arrays
   * and the colours in Uint32Arrays; null before joining.
   */
  draw({ outlines = true, solids = true, statics = true } = {}) {
    const m = this.module;
    const p = this.sizePtr;
    const flags = (outlines ? 1 : 0) | (solids ? 2 : 0) | (statics ? 128 : 0);
    const ok = m.ccall("rc_draw", "number",
                       ["number", "number", "number", "number", "number", "number"],
                       [this.handle, flags, p, p + 4, p + 8, p + 12]);
    if (ok !== 0) return null;
    const u32 = new Uint32Array(m.HEAPU8.buffer, p, 4);
    const copy = (ptr, vertices) => new Uint8Array(m.HEAPU8.buffer, ptr, vertices * 16).slice().buffer;
    const lines = copy(u32[0], u32[1]);
    const triangles = copy(u32[2], u32[3]);
    return {
      lines: new Float32Array(lines), lineColours: new Uint32Array(lines),
      triangles: new Float32Array(triangles), triangleColours: new Uint32Array(triangles),
    };
  }

  /** Leaves the match (the server hears it) and closes the socket. */
  close(reason = "closed by the page") {
    if (this.closed) return;
    const m = this.module;
    m.ccall("rc_disconnect", null, ["number", "string", "number"],
            [this.handle, reason, performance.now()]);
    this.#flush();
    this.closed = true;
    clearInterval(this.timer);
    setTimeout(() => this.socket.close(), 50);  // the Disconnect leaves first
    m.ccall("rc_destroy", null, ["number"], [this.handle]);
    m._free(this.sizePtr);
  }

  #encode(values) {
    const bytes = new Uint8Array(this.spec.size);
    const view = new DataView(bytes.buffer);
    for (const [name, value] of Object.entries(values)) {
      const field = this.spec.fields.find((f) => f.name === name);
      if (!field) throw new Error(`setInput: the game's input has no field '${name}'`);
      const v = Math.trunc(Number(value));
      switch (field.type) {
        case "i8": view.setInt8(field.offset, v); break;
        case "u8": view.setUint8(field.offset, v); break;
        case "i16": view.setInt16(field.offset, v, true); break;
        case "u16": view.setUint16(field.offset, v, true); break;
        case "i32": view.setInt32(field.offset, v, true); break;
        case "u32": view.setUint32(field.offset, v, true); break;
      }
      if (v < field.min || v > field.max) {
        throw new Error(`setInput: ${name} = ${v} is outside [${field.min}, ${field.max}]`);
      }
    }
    return bytes;
  }

  #receive(bytes) {
    if (this.closed) return;
    const m = this.module;
    const ptr = m._malloc(Math.max(1, bytes.length));
    m.HEAPU8.set(bytes, ptr);
    m.ccall("rc_receive", null, ["number", "number", "number", "number"],
            [this.handle, ptr, bytes.length, performance.now()]);
    m._free(ptr);
    this.#pump();
  }

  #pump() {
    if (this.closed) return;
    this.module.ccall("rc_update", "number", ["number", "number"], [this.handle, performance.now()]);
    this.#flush();
    for (;;) {
      const json = this.module.ccall("rc_poll_event", "string", ["number"], [this.handle]);
      if (json === "") break;
      this.#emit(JSON.parse(json));
    }
  }

  #flush() {
    const m = this.module;
    for (;;) {
      const ptr = m.ccall("rc_next_datagram", "number", ["number", "number"],
                          [this.handle, this.sizePtr]);
      if (ptr === 0) break;
      const size = new Uint32Array(m.HEAPU8.buffer, this.sizePtr, 1)[0];
      this.outgoing.send(m.HEAPU8.slice(ptr, ptr + size));
    }
  }

  #emit(event) {
    for (const key of [event.type, "*"]) {
      for (const listener of this.listeners.get(key) || []) listener(event);
    }
  }
}

/** Loads the WebAssembly module (once per call; one module serves many clients). */
export async function loadRewind() {
  const module = await RewindClientModule();
  return new Rewind(module);
}
