// The drawing of the machine from its chain (engine export `machineSchematic`): each axis where
// it sits and which way it points, the table, the spindle and the tool, at the pose asked for.
// Drawn with Plotly (3D lines, cones and a plate) so that it can be turned and zoomed.
import type { Data, Layout } from 'plotly.js';
import type { MachineDrawing } from '@engine';
import { draw } from '../ui/plot';

const K_COLOUR = '#c2410c';
const M_COLOUR = '#1d4ed8';
const LINEAR = '#57606a';

type V = [number, number, number];
const add = (a: V, b: V, s = 1): V => [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]];

/** A line segment as a scatter3d trace. */
function segment(a: V, b: V, name: string, color: string, width: number, showlegend = true): Data {
  return {
    type: 'scatter3d', mode: 'lines', x: [a[0], b[0]], y: [a[1], b[1]], z: [a[2], b[2]], name,
    line: { color, width }, hoverinfo: 'name', showlegend,
  } as Data;
}

/** An arrow head (a cone) at `at` pointing along `dir`. */
function cone(at: V, dir: V, size: number, color: string, name: string): Data {
  return {
    type: 'cone', x: [at[0]], y: [at[1]], z: [at[2]], u: [dir[0]], v: [dir[1]], w: [dir[2]],
    sizemode: 'absolute', sizeref: size, anchor: 'tail', colorscale: [[0, color], [1, color]], showscale: false,
    hoverinfo: 'name', name, showlegend: false,
  } as Data;
}

/** A label at a point. */
function label(at: V, text: string, color: string): Data {
  return {
    type: 'scatter3d', mode: 'text', x: [at[0]], y: [at[1]], z: [at[2]], text: [text],
    textfont: { color, size: 13 }, hoverinfo: 'skip', showlegend: false,
  } as Data;
}

/** Draws the machine into `target`. */
export async function drawSchematic(target: HTMLElement, r: MachineDrawing, title: string) {
  const d = r.drawing;
  const s = d.scale;
  const data: Data[] = [];
  // The table: a square plate at the table centre, in its frame.
  const [u, v] = d.tableFrame as [V, V, V];
  const c = d.tableCentre as V;
  const h = 0.35 * s;
  const corners: V[] = [add(add(c, u, -h), v, -h), add(add(c, u, h), v, -h), add(add(c, u, h), v, h), add(add(c, u, -h), v, h)];
  data.push({
    type: 'mesh3d', x: corners.map((p) => p[0]), y: corners.map((p) => p[1]), z: corners.map((p) => p[2]),
    i: new Uint8Array([0, 0]), j: new Uint8Array([1, 2]), k: new Uint8Array([2, 3]), color: '#b8c7d6', opacity: 0.7, name: 'table', hoverinfo: 'name', showlegend: true,
  } as Data);
  // The tool from its tip to the spindle nose, then the spindle.
  const tip = d.toolTip as V;
  const nose = d.spindleNose as V;
  const dir = d.toolDirection as V;
  data.push(segment(tip, nose, 'tool', '#111111', 8));
  // In a head the spindle runs from its nose to the tilting axis (M); else a stub above the nose.
  const pivot = d.axes.find((a) => a.role === 'M' && a.side === 'spindle');
  const top = pivot ? (pivot.origin as V) : add(nose, dir, 0.3 * s);
  data.push(segment(nose, top, pivot ? 'spindle (to the pivot)' : 'spindle', '#8c959f', 18));
  // The axes: rotary ones as long lines through the axis with an arrow for their positive sense,
  // linear ones as arrows from their place.
  for (const a of d.axes) {
    const o = a.origin as V;
    const e = a.direction as V;
    const side = a.side === 'table' ? 'moves the table' : 'moves the spindle';
    if (a.motion === 'rotary') {
      const colour = a.role === 'K' ? K_COLOUR : M_COLOUR;
      const name = `${a.name} (${a.role}), ${a.side === 'table' ? 'in the table' : 'in the head'}`;
      data.push(segment(add(o, e, -0.6 * s), add(o, e, 0.6 * s), name, colour, 6));
      data.push(cone(add(o, e, 0.6 * s), e, 0.08 * s, colour, name));
      data.push(label(add(o, e, 0.72 * s), a.name, colour));
    } else {
      const end = add(o, e, 0.25 * s);
      data.push(segment(o, end, `${a.name}: ${side}`, LINEAR, 3, false));
      data.push(cone(end, e, 0.05 * s, LINEAR, `${a.name}: ${side}`));
      data.push(label(add(end, e, 0.06 * s), a.name, LINEAR));
    }
  }
  await draw(target, title, data, {
    scene: {
      aspectmode: 'data',
      xaxis: { title: { text: 'X (mm)' } }, yaxis: { title: { text: 'Y (mm)' } }, zaxis: { title: { text: 'Z (mm)' } },
      camera: { eye: { x: 1.9, y: -2.1, z: 1.0 }, center: { x: 0, y: 0, z: -0.05 } },
    },
    margin: { l: 0, r: 0, b: 0 },
    legend: { x: 0, y: 1, xanchor: 'left', bgcolor: 'rgba(255,255,255,0.75)', font: { size: 11 } },
  } as Partial<Layout>, 'machine-schematic');
}
