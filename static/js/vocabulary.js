/**
 * The kitchen's words as the server sends them, spelled once for the browser: what a grill, board or sink shows
 * (`state.cells[].station.state`), and the terrain of each character of a layout grid (the instructions' example
 * kitchen). They are the planner's (planner/vocabulary.py); tests/static/test_client_sources.py holds this module
 * to it. The painters' tables keyed by terrain and object names are held to the same words by the same tests.
 */

export const STATE = Object.freeze({
  EMPTY: "empty", COOKING: "cooking", READY: "ready", CHOPPING: "chopping", WASHING: "washing", CLEAN: "clean",
});

/** Whether a station shows nothing on it (no station at all counts as empty). */
export function isEmpty(station) {
  return !station || station.state === STATE.EMPTY;
}

/** Whether a station's work is done: a steak ready, an onion chopped, a plate clean. */
export function isDone(station) {
  return !!station && (station.state === STATE.READY || station.state === STATE.CLEAN);
}

export const FLOOR = "floor";
export const COUNTER = "counter";

/** A layout grid's character → the terrain's name. */
export const TERRAIN_OF_CHAR = Object.freeze({
  X: COUNTER, " ": FLOOR, O: "onion", M: "meat", D: "plate", P: "grill", B: "board", W: "sink", S: "serve",
});
