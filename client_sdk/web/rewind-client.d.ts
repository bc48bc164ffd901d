// SPDX-License-Identifier: MIT
// Types of rewind-client.js, Rewind's client SDK for browser players.

/** One field of a game's input (the game's InputSpec). */
export interface InputField {
  name: string;
  type: "i8" | "u8" | "i16" | "u16" | "i32" | "u32";
  /** Byte offset in the input. */
  offset: number;
  /** The range the server accepts, inclusive. */
  min: number;
  max: number;
}

export interface InputSpec {
  name: string;
  /** Bytes, at most 32. */
  size: number;
  fields: InputField[];
}

/** Simulated network faults on both directions, for tests. */
export interface Faults {
  /** One-way delay added to every datagram, ms. */
  latencyMs?: number;
  /** Uniform +- variation of the delay, ms. */
  jitterMs?: number;
  /** Probability in [0, 1] that a datagram is dropped. */
  loss?: number;
  /** Seed of the fault stream (the same seed, the same fates). */
  seed?: number;
}

export interface ConnectOptions {
  /** ws:// or wss:// URL of the server's WebSocket endpoint and match:
   *  e.g. "wss://host:7800/matches/duel-7" (rewind-server --websocket). */
  url: string;
  /** The connect token from the game's backend (rewind-token mint, or the
   *  backend's own minting), hex or bytes. Omitted: a tokenless local server. */
  token?: string | Uint8Array;
  /** The game the server hosts, e.g. "crates". */
  game: string;
  /** Shown in the server's logs; at most 64 bytes. */
  name?: string;
  /** A read-only seat that verifies every final tick. */
  spectator?: boolean;
  /** Rollback depth in ticks, [16, 1024]; 96 by default. */
  snapshotTicks?: number;
  /** How often the client steps on its own, ms; 4 by default. */
  updateEveryMs?: number;
  faults?: Faults;
}

export type RewindEventType =
  | "joined" | "matchStarted" | "finalTick" | "desync" | "resynced" | "matchEnded"
  | "rejected" | "disconnected" | "resyncRefused" | "socketClosed";

export interface RewindEvent {
  type: RewindEventType;
  tick: number;
  player: number;
  /** Hex, 16 digits: our checksum and the server's for a desync. */
  localChecksum: string;
  serverChecksum: string;
  /** Why the match ended, the join was refused or the client gave up. */
  reason: string;
}

export interface ClientStatus {
  phase: "idle" | "joining" | "lobby" | "running" | "ending" | "ended";
  /** Our slot; a spectator's seat is past the player slots. */
  player: number;
  /** The predicted present tick, and its checksum (hex). */
  tick: number;
  checksum: string;
  rttMs: number;
  rollbacks: number;
  resimulatedTicks: number;
  ticksAhead: number;
  inputLeadTicks: number;
  finalTicksVerified: number;
  finalTicksResynced: number;
  desyncs: number;
  resyncs: number;
  resyncsRefused: number;
  packetsSent: number;
  packetsReceived: number;
  packetsRejected: number;
  datagramsDropped: number;
  lastFinalTick: number;
  /** WebSocket payload bytes, both ways. */
  bytesIn: number;
  bytesOut: number;
}

/** Vertices of the predicted present: x, y, z float32 and a colour
 *  (0xRRGGBBAA) per 16 bytes; index 4k..4k+2 of the floats, 4k+3 of the colours. */
export interface DrawBuffers {
  lines: Float32Array;
  lineColours: Uint32Array;
  triangles: Float32Array;
  triangleColours: Uint32Array;
}

export interface RewindClient {
  on(type: RewindEventType | "*", listener: (event: RewindEvent) => void): RewindClient;
  /** By the game's field names (missing ones are 0), or the raw bytes.
   *  Throws when the game's spec refuses it. */
  setInput(input: Record<string, number> | Uint8Array): void;
  status(): ClientStatus | null;
  draw(options?: { outlines?: boolean; solids?: boolean; statics?: boolean }): DrawBuffers | null;
  close(reason?: string): void;
}

export interface WarmUpOptions {
  /** Ticks to step, 600 by default. */
  ticks?: number;
  /** Player slots of the throwaway match, 4 by default. */
  players?: number;
  /** Ticks per slice between yields to the page, 8 by default. */
  sliceTicks?: number;
}

export interface Rewind {
  inputSpec(game: string): InputSpec;
  /** Steps a throwaway match of `game` in slices before a match, so the
   *  browser has optimized the step's code when the match needs it. */
  warmUp(game: string, options?: WarmUpOptions): Promise<void>;
  connect(options: ConnectOptions): RewindClient;
}

/** Loads the WebAssembly module; one serves any number of clients. */
export function loadRewind(): Promise<Rewind>;
