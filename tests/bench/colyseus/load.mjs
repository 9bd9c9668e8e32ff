// The Colyseus side's players (issue 39's peer benchmark): CLIENTS clients join rooms of 8
// ("arena", joinOrCreate: the rooms fill one after another, as fts-bot's rooms of 8 do)
// and each sends its input 20 times a second (fts-bot sends about 21 frames a second),
// turning to a new direction about once a second, for SECONDS seconds.
//
// usage: node load.mjs PORT CLIENTS SECONDS
// Prints {"joined":CLIENTS} once every client is in, and at the end
// {"patches":N,"clients":C} (state patches received by all clients).
import { Client } from "@colyseus/sdk";

const [port, clients, seconds] = process.argv.slice(2).map(Number);
let patches = 0;
let seed = 12345;
const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 4294967296);

const rooms = [];
for (let i = 0; i < clients; i++) {
  // One at a time: joinOrCreate fills a room before the next is made.
  const room = await new Client(`ws://127.0.0.1:${port}`).joinOrCreate("arena");
  room.onStateChange(() => patches++);
  rooms.push({ room, dx: 1, dy: 0 });
}
console.log(JSON.stringify({ joined: rooms.length }));

let ticks = 0;
const timer = setInterval(() => {
  ticks++;
  for (const r of rooms) {
    if (random() < 0.05) {
      r.dx = Math.floor(random() * 3) - 1;
      r.dy = Math.floor(random() * 3) - 1;
    }
    r.room.send("input", { dx: r.dx, dy: r.dy });
  }
}, 50);

setTimeout(async () => {
  clearInterval(timer);
  console.log(JSON.stringify({ patches, clients: rooms.length, input_rounds: ticks }));
  await Promise.all(rooms.map((r) => r.room.leave().catch(() => {})));
  process.exit(0);
}, seconds * 1000);
