/**
 * Colours of the kitchen drawing. Hues come from the Okabe–Ito palette, which stays distinguishable
 * under the common colour-vision deficiencies; every station and object also has its own shape, so
 * nothing is told apart by colour alone. Pure black is reserved for cells out of view.
 */

export const OUT_OF_VIEW = "#000000";

export const OKABE_ITO = {
  orange: "#E69F00",
  sky: "#56B4E9",
  green: "#009E73",
  yellow: "#F0E442",
  blue: "#0072B2",
  vermillion: "#D55E00",
  purple: "#CC79A7",
};

export const COLORS = {
  floor: "#EFEAE2",
  floorLine: "#DCD4C8",
  counter: "#C9B79C",
  counterEdge: "#9A8669",
  counterTop: "#D8C8AE",
  crate: "#8A6440",
  crateLine: "#6B4A2C",
  grillBody: "#70757A",
  grillBar: "#3E4246",
  grillHot: OKABE_ITO.orange,
  board: "#E9C98B",
  boardEdge: "#B08A4C",
  knife: "#9AA3AA",
  sinkBasin: OKABE_ITO.sky,
  sinkEdge: "#2F7FAE",
  tap: "#7C858C",
  serve: OKABE_ITO.green,
  serveEdge: "#00684C",
  onion: OKABE_ITO.purple,
  onionLine: "#8E4474",
  meatRaw: OKABE_ITO.vermillion,
  meatCooked: "#6E3512",
  fat: "#FBE8DC",
  plate: "#FFFFFF",
  plateRim: "#8C8C8C",
  cleanRim: OKABE_ITO.blue,
  dirt: "#7A5230",
  garnish: OKABE_ITO.green,
  human: OKABE_ITO.blue,
  humanEdge: "#003E63",
  hat: "#FFFFFF",
  robot: OKABE_ITO.orange,
  robotEdge: "#7A5400",
  visor: "#1E2A33",
  ink: "#1B1B1B",
  badge: OKABE_ITO.green,
  barBack: "rgba(20, 20, 20, 0.55)",
  barCook: OKABE_ITO.orange,
  barChop: OKABE_ITO.yellow,
  barWash: OKABE_ITO.sky,
  fovEdge: OKABE_ITO.yellow,
};
