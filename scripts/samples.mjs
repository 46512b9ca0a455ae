// `node scripts/samples.mjs [dir]`: writes the sample toolpaths of public/samples/ (or of `dir`) (CL data in
// workpiece coordinates: tool tip in mm, unit tool axis from the tip towards the spindle). The
// geometry is written out here so that anyone can check what the samples are; docs/science.md explains
// how the twelve rotary-axis types rank on them.
import { writeFileSync } from 'node:fs';

const dir = process.argv[2] ? new URL(`file://${process.argv[2].replace(/\/?$/, '/')}`) : new URL('../public/samples/', import.meta.url);
const out = (name) => new URL(name, dir);
const rad = (d) => (d * Math.PI) / 180;
const f = (x) => (Math.abs(x) < 5e-7 ? '0' : x.toFixed(6).replace(/0+$/, '').replace(/\.$/, ''));
const unit = ([x, y, z]) => {
  const n = Math.hypot(x, y, z);
  return [x / n, y / n, z / n];
};

/**
 * Impeller-like swarf path over a hub: 6 blades round Z, each finished by the flank of the tool
 * along its ruling lines. A blade's ruling at parameter t ∈ [0, 1] runs from the hub (radius
 * 30 mm, height 40·t mm) to the shroud (radius 70 mm, height 10 + 25·t mm); the blade turns by
 * 50° about Z from its inlet (t = 0) to its outlet (t = 1), the shroud lagging the hub by 20°
 * (the twist that makes the tool axis swing). Tool tip: 2 mm above the hub end of the ruling;
 * tool axis: from the hub end towards a point 40 mm above the shroud end (tilted up from the
 * ruling, as a holder clearing the hub needs). 0.5° of blade turn per point (101 points a blade),
 * down one blade and back up the next (zig-zag), linked by 30 moves in the air that take the
 * tip along a straight line and the axis along the great circle to the next blade's first
 * point: 751 points in all.
 */
function impeller() {
  const lines = ['PARTNO/IMPELLER SWARF SAMPLE (scripts/samples.mjs)', 'UNITS/MM', 'MULTAX/ON', 'CUTTER/10'];
  const blades = 6;
  const n = 101;
  let last = null;
  for (let b = 0; b < blades; b++) {
    const phi0 = (360 / blades) * b;
    for (let s = 0; s < n; s++) {
      const t = b % 2 === 0 ? s / (n - 1) : 1 - s / (n - 1);
      const hubPhi = rad(phi0 + 50 * t);
      const shroudPhi = rad(phi0 + 50 * t - 20 * (1 - t));
      const hub = [30 * Math.cos(hubPhi), 30 * Math.sin(hubPhi), 40 * t];
      const shroud = [70 * Math.cos(shroudPhi), 70 * Math.sin(shroudPhi), 10 + 25 * t];
      const axis = unit([shroud[0] - hub[0], shroud[1] - hub[1], shroud[2] - hub[2] + 40]);
      const tip = [hub[0], hub[1], hub[2] + 2];
      if (s === 0 && last) {
        // The link from the previous blade: tip on a straight line 20 mm up, axis on the great
        // circle (normalised linear interpolation of two unit vectors keeps it on that circle).
        for (let j = 1; j < 30; j++) {
          const u = j / 30;
          const lift = 20 * Math.sin(Math.PI * u);
          const p = [0, 1, 2].map((c) => last.tip[c] + u * (tip[c] - last.tip[c]) + (c === 2 ? lift : 0));
          const a = unit([0, 1, 2].map((c) => last.axis[c] + u * (axis[c] - last.axis[c])));
          lines.push(`GOTO/${[...p, ...a].map(f).join(',')}`);
        }
      }
      lines.push(`GOTO/${[...tip, ...axis].map(f).join(',')}`);
      last = { tip, axis };
    }
  }
  lines.push('FINI');
  return lines.join('\n') + '\n';
}

/**
 * A dome finished along one meridian that passes 0.3° beside its top: the tool normal to a
 * sphere of radius 50 mm centred at the origin, the tool axis tilting from 40° on one side to 40°
 * on the other in 1° steps (81 points). Types whose K axis is Z (C on the table or the head) must
 * turn K by nearly 180° as the tool passes the vertical: a flip; the others pass smoothly.
 */
function dome() {
  const lines = ['# x, y, z (mm), i, j, k: tool tip and unit tool axis (scripts/samples.mjs)', 'x,y,z,i,j,k'];
  const offset = rad(0.3);
  const az = rad(30);
  const d = [Math.cos(az), Math.sin(az), 0];
  const side = [-Math.sin(az), Math.cos(az), 0];
  for (let i = 0; i <= 80; i++) {
    const t = rad(-40 + i);
    const up = [side[0] * Math.sin(offset), side[1] * Math.sin(offset), Math.cos(offset)];
    const axis = unit([up[0] * Math.cos(t) + d[0] * Math.sin(t), up[1] * Math.cos(t) + d[1] * Math.sin(t), up[2] * Math.cos(t)]);
    const tip = axis.map((c) => 50 * c);
    lines.push([...tip, ...axis].map(f).join(','));
  }
  return lines.join('\n') + '\n';
}

writeFileSync(out('impeller-swarf.apt'), impeller());
writeFileSync(out('dome-past-the-pole.csv'), dome());
console.log(`wrote impeller-swarf.apt and dome-past-the-pole.csv in ${dir.pathname}`);
