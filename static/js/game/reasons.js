/**
 * Words for why a task cannot work (docs/protocol.md, `blocked` messages and `hello.needs`): what a task needs
 * in the cook's hands, and why an interaction did nothing, judged by the server from the cell the cook faces
 * (always in view). Participant-facing text lives here so the top-down and first-person pages say the same.
 */

import { heldLabel, OBJECTS } from "../labels.js";

const NEEDS_TEXT = {
  nothing: (held) => `Your hands are full (${heldLabel(held)}): put it down first`,
  something: () => "Your hands are empty: there is nothing to put down",
};

/**
 * Why a task that needs `need` in hand (`nothing`, `something` or an object, from `hello.needs`) cannot work
 * while the cook holds `held`; null when it can.
 */
export function handsReason(need, held) {
  const holding = held || null;
  if (need === "nothing") return holding === null ? null : NEEDS_TEXT.nothing(holding);
  if (need === "something") return holding !== null ? null : NEEDS_TEXT.something();
  if (!need || holding === need) return null;
  return `You need ${OBJECTS[need] || heldLabel(need)} in your hands`;
}

/** "the steak", "the chopped onion": what the robot took or worked on, named as a thing the participant knows. */
const THE = {
  steak: "the steak", garnish: "the chopped onion", onion: "the onion", meat: "the raw meat",
  dirty_plate: "the dirty plate", clean_plate: "the clean plate", steak_plate: "the plated steak",
  dish: "the finished dish",
};
const the = (item) => THE[item] || `the ${String(item || "food").replaceAll("_", " ")}`;
const PUT_ON = { grill: "on the grill", board: "on the board", sink: "in the sink", counter: "on the counter" };
const DONE = { onion: "The robot already chopped the onion", dirty_plate: "The robot already washed the plate" };

const REASONS = {
  hands_full: (item) => (item ? `Your hands are full (${heldLabel(item)})` : "Your hands are full"),
  hands_empty: () => "Your hands are empty",
  needs_item: (item) => `You need ${OBJECTS[item] || heldLabel(item)} in your hands`,
  nothing_there: () => "There is nothing to use there",
  counter_empty: () => "There is nothing on this counter",
  grill_busy: () => "The grill is busy",
  steak_cooking: () => "The steak is still cooking",
  board_busy: () => "The board is busy",
  nothing_to_chop: () => "There is no onion on the board",
  no_garnish: () => "There is no onion on the board",
  not_chopped: () => "The onion is not chopped yet",
  already_chopped: () => "The onion is already chopped",
  sink_busy: () => "The sink is busy",
  nothing_to_wash: () => "There is no plate in the sink",
  already_washed: () => "The plate is already clean",
  no_clean_plate: () => "You have not seen a clean plate yet",
  robot_in_way: () => "The robot is in the way",
  no_way: () => "The way there is blocked",
  unknown_place: () => "You have not seen where to do this yet: look around",
  stuck: () => "This task is not getting anywhere",
  no_steak: () => "There is no steak on the grill",
  taken_by_robot: (item, place) => `The robot took ${the(item)} from the ${place || "counter"}`,
  filled_by_robot: (item, place) => `The robot put ${OBJECTS[item] || the(item)} ${PUT_ON[place] || "there"}`,
  done_by_robot: (item) => DONE[item] || "The robot already did that",
};

/** The sentence for a `blocked` message (`reason`, `item`); a reason this page does not know still reads well. */
export function blockedText(message) {
  const words = REASONS[message.reason];
  return words ? words(message.item, message.place) : "That did not work";
}

export const BLOCKED_REASONS = Object.keys(REASONS);
