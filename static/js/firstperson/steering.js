/**
 * Keys relative to the view, as a first-person player expects them: ↑ / W steps forward, ← / A and → / D
 * turn left and right, ↓ / S turns around. Each key press is one of the world's moves (docs/domain.md §1: a
 * move turns the cook to that direction and steps into the cell if it is floor), so "turn left" is the move
 * to the cell on the left: the cook faces it, and steps into it when the floor is free. The server's
 * interrupts stay the absolute up / down / left / right (north / south / west / east) the top-down view sends.
 *
 * The direction a key means depends on where the cook will face once the moves already sent are played, so
 * the steering keeps that facing itself and takes the server's again only when every interrupt it sent has
 * been accepted and played (`state.ack` at least their `seq`, `state.queued` 0).
 */

const COMPASS = ["north", "east", "south", "west"];
const INTERRUPT = { north: "up", east: "right", south: "down", west: "left" };
/** Quarter turns clockwise from the facing for each movement key of game/keys.js. */
const QUARTERS = { up: 0, right: 1, down: 2, left: 3 };

/** Labels of the interrupt buttons in first person (the same ids as the top-down ones). */
export const RELATIVE_LABELS = { up: "Forward", left: "Turn left", down: "Turn around", right: "Turn right" };

/** The absolute direction a relative `key` means for a cook facing `facing`. */
export function directionFor(facing, key) {
  return COMPASS[(COMPASS.indexOf(facing) + QUARTERS[key]) % 4];
}

export class Steering {
  constructor() {
    this.facing = null;
    this.lastSeq = 0;
  }

  /** The server's view of the cook, from a `state` message. */
  observe(state) {
    if (this.facing === null || (state.queued === 0 && state.ack >= this.lastSeq)) this.facing = state.you.facing;
  }

  /** The interrupt to send for a key's action (`up`, `left`, … from game/keys.js, or `interact`, `stop`, …). */
  interruptFor(action) {
    if (!(action in QUARTERS) || this.facing === null) return action;
    this.facing = directionFor(this.facing, action);
    return INTERRUPT[this.facing];
  }

  /** The interrupt just translated went out with `seq` (null: not sent; the next state corrects the facing).
   * A rejected one (queue full) never reaches `state.ack`; the next accepted message (a heartbeat, every
   * 2 s) does, and the facing is the server's again. */
  sent(seq) {
    if (seq !== null) this.lastSeq = Math.max(this.lastSeq, seq);
  }
}
