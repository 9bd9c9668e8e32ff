// Fear The Sphere's peer benchmark, the Colyseus side (issue 39): rooms of the size of an
// fts-server room, doing what an fts room does each tick in the simplest fair way.
//
// A room: up to 8 players and ENEMIES enemy balls on a 500 x 300 platform; a fixed step
// at 100 Hz (setSimulationInterval 10 ms): each player's ball thrusts toward its last
// input (accel 200 u/s^2, top speed 170 u/s, as fts's defaults), each enemy toward a goal
// it redraws when near it, friction, every pair of balls tested and an overlapping pair
// bounced elastically by mass, a ball off the platform put back at a free spot. The state
// (a MapSchema of balls: x, y, vx, vy as float32) goes to the clients as Colyseus schema
// patches at 20 Hz (setPatchRate 50 ms) over WebSocket (no TLS). fts-server does more in
// a tick (its exact collision model, the coins and shop, per-client delta snapshots,
// each sealed with ChaCha20-Poly1305 (IETF)): the comparison is its CPU per client against
// this simpler room's.
//
// usage: node server.mjs PORT ENEMIES
// Prints {"listening":PORT} once ready and {"sent_bytes":N,"sent_messages":M} on SIGUSR2
// (gracefullyShutdown off: Colyseus would otherwise take SIGUSR2 as a signal to stop)
// (what the server wrote to its WebSockets: frame payloads, without WebSocket, TCP or IP
// headers; fts's bytes_out is likewise UDP payloads).
import { Server, Room } from "@colyseus/core";
import { WebSocketTransport } from "@colyseus/ws-transport";
import { Schema, MapSchema, defineTypes } from "@colyseus/schema";
import { WebSocket } from "ws";

const port = Number(process.argv[2] || 2567);
const enemies = Number(process.argv[3] || 16);

let sentBytes = 0;
let sentMessages = 0;
const send = WebSocket.prototype.send;
WebSocket.prototype.send = function (data, ...rest) {
  sentBytes += data.byteLength ?? data.length ?? 0;
  sentMessages += 1;
  return send.call(this, data, ...rest);
};
process.on("SIGUSR2", () => console.log(JSON.stringify({ sent_bytes: sentBytes, sent_messages: sentMessages })));

class Ball extends Schema {}
defineTypes(Ball, { x: "float32", y: "float32", vx: "float32", vy: "float32", r: "uint8" });
class ArenaState extends Schema {}
defineTypes(ArenaState, { tick: "uint32", balls: { map: Ball } });

const W = 500, H = 300, DT = 0.01, ACCEL = 200, VMAX = 170, FRICTION = 0.4;

// A small seeded generator (xorshift32): every room the same from its seed.
function rng(seed) {
  let s = seed >>> 0 || 1;
  return () => {
    s ^= s << 13; s >>>= 0; s ^= s >>> 17; s ^= s << 5; s >>>= 0;
    return s / 4294967296;
  };
}

class Arena extends Room {
  maxClients = 8;

  onCreate() {
    const state = new ArenaState();
    state.tick = 0;
    state.balls = new MapSchema();
    this.state = state;
    this.random = rng(this.roomId.split("").reduce((h, c) => (h * 31 + c.charCodeAt(0)) >>> 0, 7));
    this.bodies = new Map();  // id -> {ball, mass, dx, dy, goal}
    for (let i = 0; i < enemies; i++) this.add(`e${i}`, 30, false);
    this.onMessage("input", (client, m) => {
      const b = this.bodies.get(client.sessionId);
      if (b && m && Number.isFinite(m.dx) && Number.isFinite(m.dy)) {
        b.dx = Math.sign(m.dx);
        b.dy = Math.sign(m.dy);
      }
    });
    this.setPatchRate(50);
    this.setSimulationInterval(() => this.step(), 10);
  }

  add(id, mass, player) {
    const ball = new Ball();
    ball.r = 10;
    this.place(ball);
    ball.vx = 0;
    ball.vy = 0;
    this.state.balls.set(id, ball);
    this.bodies.set(id, { ball, mass, dx: 0, dy: 0, player, gx: W / 2, gy: H / 2 });
  }

  place(ball) {
    for (let tries = 0; tries < 50; tries++) {
      ball.x = 50 + this.random() * (W - 100);
      ball.y = 50 + this.random() * (H - 100);
      let free = true;
      for (const o of this.bodies.values())
        if (o.ball !== ball && Math.hypot(o.ball.x - ball.x, o.ball.y - ball.y) < 25) free = false;
      if (free) return;
    }
  }

  onJoin(client) { this.add(client.sessionId, 30, true); }

  onLeave(client) {
    this.bodies.delete(client.sessionId);
    this.state.balls.delete(client.sessionId);
  }

  step() {
    this.state.tick++;
    const list = [...this.bodies.values()];
    for (const b of list) {
      const ball = b.ball;
      if (!b.player) {
        if (Math.abs(ball.x - b.gx) < 3) b.gx = 100 + this.random() * (W - 200);
        if (Math.abs(ball.y - b.gy) < 3) b.gy = 60 + this.random() * (H - 120);
        b.dx = Math.sign(b.gx - ball.x);
        b.dy = Math.sign(b.gy - ball.y);
      }
      let vx = ball.vx + b.dx * ACCEL * DT, vy = ball.vy + b.dy * ACCEL * DT;
      vx -= vx * FRICTION * DT;
      vy -= vy * FRICTION * DT;
      const v = Math.hypot(vx, vy);
      if (v > VMAX) { vx *= VMAX / v; vy *= VMAX / v; }
      ball.vx = vx;
      ball.vy = vy;
      ball.x += vx * DT;
      ball.y += vy * DT;
    }
    for (let i = 0; i < list.length; i++) {
      for (let j = i + 1; j < list.length; j++) {
        const a = list[i], c = list[j];
        const nx = c.ball.x - a.ball.x, ny = c.ball.y - a.ball.y;
        const d = Math.hypot(nx, ny), reach = a.ball.r + c.ball.r;
        if (d >= reach || d === 0) continue;
        const ux = nx / d, uy = ny / d;
        const rel = (a.ball.vx - c.ball.vx) * ux + (a.ball.vy - c.ball.vy) * uy;
        if (rel <= 0) continue;
        const k = (2 * rel) / (a.mass + c.mass);
        a.ball.vx -= k * c.mass * ux; a.ball.vy -= k * c.mass * uy;
        c.ball.vx += k * a.mass * ux; c.ball.vy += k * a.mass * uy;
      }
    }
    for (const b of list) {
      const ball = b.ball;
      if (ball.x < 0 || ball.x > W || ball.y < 0 || ball.y > H) {
        this.place(ball);
        ball.vx = 0;
        ball.vy = 0;
      }
    }
  }
}

const server = new Server({ transport: new WebSocketTransport(), greet: false, gracefullyShutdown: false });
server.define("arena", Arena);
await server.listen(port);
console.log(JSON.stringify({ listening: port }));
