// Export of what a plot shows: CSV of its data (columns with units, from the axis titles) and
// PNG through Plotly. Nothing leaves the browser: files are made from Blobs and downloaded.

interface Trace {
  type?: string;
  name?: string;
  x?: ArrayLike<unknown>;
  y?: ArrayLike<unknown>;
  /** Polar traces: the angle, and the value shown (`customdata` when the radius is scaled). */
  theta?: ArrayLike<unknown>;
  r?: ArrayLike<unknown>;
  customdata?: ArrayLike<unknown>;
  yaxis?: string;
  z?: ArrayLike<ArrayLike<unknown>>;
  showlegend?: boolean;
}
interface Graph extends HTMLElement {
  data?: Trace[];
  layout?: { xaxis?: { title?: { text?: string } }; yaxis?: { title?: { text?: string } }; title?: { text?: string }; meta?: { csvX?: string; csvY?: string; titles?: Record<string, string> } } & Record<string, unknown>;
}

function cell(v: unknown): string {
  if (v === null || v === undefined) return '';
  if (typeof v === 'number') return Number.isFinite(v) ? String(v) : '';
  const s = String(v);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

const plain = (t: string | undefined, fallback: string) => (t ?? fallback).replace(/<br>/g, ' ').replace(/<[^>]+>/g, '');

/**
 * CSV of a Plotly graph's data. Line and bar traces: one x column, then one column per trace
 * (traces sharing the same x), or long form (trace, x, value, the quantity and unit of its own
 * axis; gaps left out) when their x differ. Units are those of the data as drawn (µm), not the
 * ticks' relabelling in mm. Heat maps: the
 * first row holds the x values, each further row a y value then z along x.
 */
export function graphCsv(gd: Graph): string {
  // A polar trace is exported as angle and value (its `customdata` when the radius is a scaled
  // drawing of it); `layout.meta.csvX`/`csvY` name them.
  const data = (gd.data ?? []).map((t) => (t.theta ? { ...t, x: t.theta, y: t.customdata ?? t.r } : t));
  // Titles as drawn with the data's units (`meta.titles`, kept by plot.ts's draw), not the
  // ticks' relabelling in mm.
  const titles = gd.layout?.meta?.titles ?? {};
  const xt = plain(gd.layout?.meta?.csvX ?? titles.xaxis ?? gd.layout?.xaxis?.title?.text, 'x');
  const yt = plain(gd.layout?.meta?.csvY ?? titles.yaxis ?? gd.layout?.yaxis?.title?.text, 'y');
  /** The unit column of a trace: its own y axis's title (plots with several y axes). */
  const yOf = (t: Trace) => {
    if (!t.yaxis || t.yaxis === 'y') return yt;
    const key = `yaxis${t.yaxis.slice(1)}`;
    const text = titles[key] ?? (gd.layout?.[key] as { title?: { text?: string } } | undefined)?.title?.text;
    return text ? plain(text, yt) : yt;
  };
  const lines: string[] = [];
  const heat = data.find((t) => t.type === 'heatmap' || t.type === 'surface');
  if (heat && heat.z) {
    const name = plain(heat.name, 'z');
    lines.push(`# ${name}; rows: ${yt}; columns: ${xt}`);
    const xs = Array.from(heat.x ?? []);
    lines.push([`${yt} \\ ${xt}`, ...xs].map(cell).join(','));
    const ys = Array.from(heat.y ?? []);
    Array.from(heat.z).forEach((row, i) => lines.push([ys[i], ...Array.from(row)].map(cell).join(',')));
    return lines.join('\n') + '\n';
  }
  const series = data.filter((t) => t.y);
  const sameX =
    series.length > 0 &&
    series.every((t) => {
      const a = Array.from(t.x ?? []);
      const b = Array.from(series[0].x ?? []);
      return a.length === b.length && a.every((v, i) => v === b[i]);
    });
  if (sameX) {
    lines.push([xt, ...series.map((t, i) => `${plain(t.name, `trace ${i + 1}`)} [${yOf(t)}]`)].map(cell).join(','));
    const xs = Array.from(series[0].x ?? []);
    xs.forEach((x, i) => lines.push([x, ...series.map((t) => Array.from(t.y ?? [])[i])].map(cell).join(',')));
  } else {
    // Long form: each row says what its value is and in which unit (its trace's own y axis).
    lines.push(['trace', xt, 'value', 'quantity (unit)'].map(cell).join(','));
    for (const [i, t] of series.entries()) {
      const xs = Array.from(t.x ?? []);
      const of = yOf(t);
      Array.from(t.y ?? []).forEach((y, j) => {
        if (y !== null && y !== undefined) lines.push([plain(t.name, `trace ${i + 1}`), xs[j], y, of].map(cell).join(','));
      });
    }
  }
  return lines.join('\n') + '\n';
}

export function download(filename: string, content: BlobPart, type: string) {
  const url = URL.createObjectURL(new Blob([content], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = filename;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
