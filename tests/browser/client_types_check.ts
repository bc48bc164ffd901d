// SPDX-License-Identifier: MIT
// A browser game's use of the client SDK, type-checked against
// rewind-client.d.ts as a game would see it: the package imported by its
// name (@rewind/client, resolved through its package.json), under
// `strict`. The lines marked @ts-expect-error are misuses the declarations
// must refuse; tsc fails when one of them is accepted.
import { loadRewind } from "@rewind/client";
import type {
  ClientStatus,
  DrawBuffers,
  InputSpec,
  Rewind,
  RewindClient,
  RewindEvent,
  RewindEventType,
} from "@rewind/client";

export async function play(token: string, url: string): Promise<ClientStatus | null> {
  const rewind: Rewind = await loadRewind();
  const spec: InputSpec = rewind.inputSpec("crates");
  await rewind.warmUp("crates", { ticks: 300, players: 2 });
  const names: string[] = spec.fields.map((field) => `${field.name}:${field.type}[${field.min},${field.max}]`);
  console.log(spec.size, names.join(" "));

  const client: RewindClient = rewind.connect({
    url,
    token,
    game: "crates",
    name: "typed page",
    snapshotTicks: 96,
    faults: { latencyMs: 40, jitterMs: 10, loss: 0.03, seed: 7 },
  });
  client
    .on("matchStarted", (event: RewindEvent) => console.log("started at", event.tick))
    .on("desync", (event) => console.warn(event.localChecksum, event.serverChecksum))
    .on("*", (event) => {
      const type: RewindEventType = event.type;
      if (type === "matchEnded") console.log(event.reason);
    });
  client.setInput({ axis_x: 100, axis_y: -40, buttons: 1 });
  client.setInput(new Uint8Array([1, 2, 3]));

  const frame: DrawBuffers | null = client.draw({ outlines: true, statics: false });
  if (frame !== null) {
    const vertices: number = frame.triangles.length / 4;
    const colour: number = frame.triangleColours[3] ?? 0;
    console.log(vertices, colour.toString(16));
  }
  const status = client.status();
  if (status !== null) {
    const phase: "idle" | "joining" | "lobby" | "running" | "ending" | "ended" = status.phase;
    console.log(phase, status.rttMs, status.finalTicksVerified, status.bytesIn + status.bytesOut);
  }
  client.close("the page closed");
  return status;
}

export function misuses(rewind: Rewind, client: RewindClient): void {
  // @ts-expect-error: the game is required
  rewind.connect({ url: "ws://localhost:7800/matches/m" });
  // @ts-expect-error: a token is hex text or bytes, not a number
  rewind.connect({ url: "ws://localhost:7800/matches/m", game: "crates", token: 42 });
  // @ts-expect-error: no such event
  client.on("tick", () => {});
  // @ts-expect-error: an input is named fields or bytes, not text
  client.setInput("left");
  // @ts-expect-error: a warm-up's length is a number of ticks
  void rewind.warmUp("crates", { ticks: "long" });
  // @ts-expect-error: the faults take numbers
  rewind.connect({ url: "u", game: "crates", faults: { loss: "3%" } });
  const status = client.status();
  // @ts-expect-error: status() is null before joining
  console.log(status.tick);
}
