/**
 * Smooth motion between the server's ticks (5 Hz by default): each new pose of the cook or the robot is
 * reached over one tick period from wherever it is drawn now, position in a straight line and heading along
 * the shorter way round, so walking and turning glide instead of jumping a cell at a time. A pose that jumps
 * more than one cell (a resumed round, the robot coming into view elsewhere) is shown at once.
 */

import { YAW } from "./agents.js";

const TAU = Math.PI * 2;

/** The pose of an agent in the `state` message (grid x, y and facing) in scene terms: x, z and yaw. */
export function poseOf(agent) {
  return { x: agent.x, z: agent.y, yaw: YAW[agent.facing] ?? 0 };
}

/** `b − a` for angles, the shorter way round (in (−π, π]). */
export function turn(a, b) {
  let d = (b - a) % TAU;
  if (d > Math.PI) d -= TAU;
  if (d <= -Math.PI) d += TAU;
  return d;
}

export function lerpPose(from, to, t) {
  const k = Math.min(Math.max(t, 0), 1);
  return { x: from.x + (to.x - from.x) * k, z: from.z + (to.z - from.z) * k, yaw: from.yaw + turn(from.yaw, to.yaw) * k };
}

/** One agent's drawn pose: `goTo` a new target at time `now`; `at(now)` the pose to draw. */
export class Glide {
  constructor() {
    this.from = null;
    this.to = null;
    this.start = 0;
    this.duration = 1;
  }

  goTo(target, now, duration) {
    const current = this.to ? this.at(now) : null;
    const far = !current || Math.hypot(target.x - current.x, target.z - current.z) > 1.5;
    this.from = far ? target : current;
    this.to = target;
    this.start = now;
    this.duration = Math.max(duration, 1);
  }

  /** Show `target` at once (no glide). */
  snap(target) {
    this.from = target;
    this.to = target;
  }

  at(now) {
    if (!this.to) return null;
    return lerpPose(this.from, this.to, (now - this.start) / this.duration);
  }

  moving(now) {
    return Boolean(this.to) && now - this.start < this.duration &&
      (this.from.x !== this.to.x || this.from.z !== this.to.z || this.from.yaw !== this.to.yaw);
  }
}
