/**
 * The two agents seen from above: the participant's cook (blue shoulders under a round white chef's hat)
 * and the robot (an orange rounded square with a dark visor and an antenna). Both show where they face —
 * the cook with a pointer, the robot with its visor and eyes — and carry what they hold in front of them.
 */

import { COLORS, OKABE_ITO } from "./palette.js";
import { drawObject } from "./items.js";

export const FACING = { north: [0, -1], south: [0, 1], east: [1, 0], west: [-1, 0] };

function vector(facing) {
  return FACING[facing] || FACING.south;
}

function drawHuman(ctx, cx, cy, s, dx, dy) {
  const tip = s * 0.47;
  const side = s * 0.13;
  const base = s * 0.24;
  ctx.beginPath();
  ctx.moveTo(cx + dx * tip, cy + dy * tip);
  ctx.lineTo(cx + dx * base - dy * side, cy + dy * base + dx * side);
  ctx.lineTo(cx + dx * base + dy * side, cy + dy * base - dx * side);
  ctx.closePath();
  ctx.fillStyle = COLORS.humanEdge;
  ctx.fill();
  const across = s * 0.36;
  const along = s * 0.22;
  ctx.beginPath();
  ctx.ellipse(cx, cy, dx !== 0 ? along : across, dx !== 0 ? across : along, 0, 0, Math.PI * 2);
  ctx.fillStyle = COLORS.human;
  ctx.fill();
  ctx.lineWidth = Math.max(1.5, s * 0.04);
  ctx.strokeStyle = COLORS.humanEdge;
  ctx.stroke();
  const hx = cx + dx * s * 0.03;
  const hy = cy + dy * s * 0.03;
  ctx.beginPath();
  ctx.arc(hx, hy, s * 0.17, 0, Math.PI * 2);
  ctx.fillStyle = COLORS.hat;
  ctx.fill();
  ctx.lineWidth = Math.max(1, s * 0.03);
  ctx.strokeStyle = COLORS.humanEdge;
  ctx.stroke();
  ctx.beginPath();
  ctx.arc(hx, hy, s * 0.09, 0, Math.PI * 2);
  ctx.strokeStyle = "rgba(0, 62, 99, 0.45)";
  ctx.lineWidth = Math.max(1, s * 0.02);
  ctx.stroke();
}

function eyes(ctx, cx, cy, s, dx, dy, dist, color) {
  const spread = s * 0.1;
  ctx.fillStyle = color;
  for (const sign of [-1, 1]) {
    ctx.beginPath();
    ctx.arc(cx + dx * dist - dy * spread * sign, cy + dy * dist + dx * spread * sign, Math.max(1.2, s * 0.035), 0, Math.PI * 2);
    ctx.fill();
  }
}

function drawRobot(ctx, cx, cy, s, dx, dy) {
  const half = s * 0.32;
  ctx.beginPath();
  ctx.roundRect(cx - half, cy - half, half * 2, half * 2, s * 0.09);
  ctx.fillStyle = COLORS.robot;
  ctx.fill();
  ctx.lineWidth = Math.max(1.5, s * 0.05);
  ctx.strokeStyle = COLORS.robotEdge;
  ctx.stroke();
  const vw = dx !== 0 ? s * 0.12 : half * 1.5;
  const vh = dy !== 0 ? s * 0.12 : half * 1.5;
  const vx = cx + dx * half * 0.6 - vw / 2;
  const vy = cy + dy * half * 0.6 - vh / 2;
  ctx.beginPath();
  ctx.roundRect(vx, vy, vw, vh, s * 0.03);
  ctx.fillStyle = COLORS.visor;
  ctx.fill();
  eyes(ctx, cx, cy, s, dx, dy, half * 0.6, OKABE_ITO.sky);
  ctx.beginPath();
  ctx.moveTo(cx - dx * s * 0.05, cy - dy * s * 0.05);
  ctx.lineTo(cx - dx * s * 0.2, cy - dy * s * 0.2);
  ctx.strokeStyle = COLORS.robotEdge;
  ctx.lineWidth = Math.max(1, s * 0.035);
  ctx.stroke();
  ctx.beginPath();
  ctx.arc(cx - dx * s * 0.2, cy - dy * s * 0.2, Math.max(1.5, s * 0.05), 0, Math.PI * 2);
  ctx.fillStyle = OKABE_ITO.vermillion;
  ctx.fill();
}

/** Draw `agent` ({x, y, facing, held}) as `kind` ("human" or "robot") in the cell square (x0, y0, s). */
export function drawAgent(ctx, kind, agent, x0, y0, s) {
  const [dx, dy] = vector(agent.facing);
  const cx = x0 + s / 2;
  const cy = y0 + s / 2;
  if (kind === "robot") drawRobot(ctx, cx, cy, s, dx, dy);
  else drawHuman(ctx, cx, cy, s, dx, dy);
  if (agent.held) {
    const off = s * 0.3;
    drawObject(ctx, agent.held, cx + dx * off + (dx === 0 ? s * 0.2 : 0), cy + dy * off + (dy === 0 ? s * 0.2 : 0), s * 0.2);
  }
}
