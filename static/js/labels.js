/**
 * Participant-facing names for the protocol's identifiers (docs/domain.md §4): subtasks grouped the way a cook
 * thinks of them, interrupts with their keys, and the objects an agent can hold.
 */

export const SUBTASK_GROUPS = [
  { title: "Pick up", subtasks: ["pickup_meat", "pickup_onion", "pickup_plate", "pickup_clean_plate",
                                 "pickup_steak", "pickup_garnish"] },
  { title: "Put down", subtasks: ["drop_meat", "drop_onion", "drop_plate", "drop_on_counter"] },
  { title: "Work and serve", subtasks: ["chop_onion", "wash_plate", "deliver_dish"] },
];

export const SUBTASKS = {
  pickup_meat: { label: "Pick up meat", hint: "Take raw meat from the meat crate." },
  pickup_onion: { label: "Pick up onion", hint: "Take an onion from the onion crate." },
  pickup_plate: { label: "Pick up plate", hint: "Take a dirty plate from the plate rack." },
  pickup_clean_plate: { label: "Pick up clean plate", hint: "Take the washed plate out of the sink." },
  pickup_steak: { label: "Pick up steak", hint: "Bring a clean plate to the grill to take the cooked steak." },
  pickup_garnish: { label: "Pick up garnish", hint: "Bring the plated steak to the board to add the chopped onion." },
  drop_meat: { label: "Meat on grill", hint: "Put the meat you hold on the grill; it then cooks by itself." },
  drop_onion: { label: "Onion on board", hint: "Put the onion you hold on the chopping board." },
  drop_plate: { label: "Plate in sink", hint: "Put the dirty plate you hold in the sink." },
  drop_on_counter: { label: "Put on counter", hint: "Put what you hold on the nearest free counter." },
  chop_onion: { label: "Chop onion", hint: "Chop the onion on the board until it is ready." },
  wash_plate: { label: "Wash plate", hint: "Wash the plate in the sink until it is clean." },
  deliver_dish: { label: "Deliver dish", hint: "Bring the finished dish to the serving counter." },
};

export function subtaskLabel(id) {
  if (!id) return "none";
  return (SUBTASKS[id] && SUBTASKS[id].label) || String(id).replaceAll("_", " ");
}

/** Interrupt actions in the order shown, each with the keys that trigger it (see game/keys.js). */
export const INTERRUPTS = [
  { id: "up", label: "Up", keys: ["↑", "W"] },
  { id: "left", label: "Left", keys: ["←", "A"] },
  { id: "down", label: "Down", keys: ["↓", "S"] },
  { id: "right", label: "Right", keys: ["→", "D"] },
  { id: "interact", label: "Interact", keys: ["Space"] },
  { id: "stay", label: "Stay", keys: ["."] },
  { id: "stop", label: "Stop task", keys: ["Esc", "Shift+S"] },
];

export const OBJECTS = {
  onion: "an onion",
  meat: "raw meat",
  dirty_plate: "a dirty plate",
  clean_plate: "a clean plate",
  steak_plate: "a plated steak",
  dish: "a finished dish",
};

export function heldLabel(held) {
  if (!held) return "nothing";
  return OBJECTS[held] || String(held).replaceAll("_", " ");
}

export const STATIONS = {
  counter: "Counter",
  onion: "Onion crate",
  meat: "Meat crate",
  plate: "Plate rack (dirty plates)",
  grill: "Grill",
  board: "Chopping board",
  sink: "Sink",
  serve: "Serving counter",
  floor: "Floor",
};
