// What the page still has to do: engine calls in flight (the engine's worker and the toolpath
// workers), edits waiting for their debounce, plots being drawn and files being fetched. When
// all are zero the page is idle: nothing it has been asked to show is still on its way.
//
// Tests read it instead of sleeping: `document.body.dataset.busy` is "0" when idle, and
// `window.__fiveaxis` holds the counters (`calls` started, `done` finished, `inFlight`,
// `waiting` debounced edits, `drawing`, `draws` finished, `fetching`) and `idle()`.

const counts = { calls: 0, done: 0, inFlight: 0, waiting: 0, drawing: 0, draws: 0, fetching: 0 };

function publish() {
  const busy = counts.inFlight + counts.waiting + counts.drawing + counts.fetching;
  if (document.body) document.body.dataset.busy = String(busy);
}

/** Whether nothing is in flight, waiting, being drawn or fetched. */
export function idle(): boolean {
  return counts.inFlight === 0 && counts.waiting === 0 && counts.drawing === 0 && counts.fetching === 0;
}

/**
 * Counts one engine call in flight; the function returned ends it (once). The end is counted a
 * task later, after the callbacks of the call's promise have run, so that a plot those callbacks
 * start drawing is counted before the call stops counting: the page never looks idle between.
 */
export function callStarted(): () => void {
  counts.calls++;
  counts.inFlight++;
  publish();
  let ended = false;
  return () => {
    if (ended) return;
    ended = true;
    setTimeout(() => {
      counts.inFlight--;
      counts.done++;
      publish();
    }, 0);
  };
}

/** Counts one plot being drawn; the function returned ends it (once). */
export function drawStarted(): () => void {
  counts.drawing++;
  publish();
  let ended = false;
  return () => {
    if (ended) return;
    ended = true;
    counts.drawing--;
    counts.draws++;
    publish();
  };
}

/** Counts `p` (a fetch, say) until it settles, a task later (see `callStarted`). */
export function track<T>(p: Promise<T>): Promise<T> {
  counts.fetching++;
  publish();
  const end = () =>
    setTimeout(() => {
      counts.fetching--;
      publish();
    }, 0);
  p.then(end, end);
  return p;
}

/**
 * A debounce that is counted while it waits: `debounced(fn, ms)` gives a function that runs
 * `fn` `ms` after its last call, and `cancel` to drop a waiting run.
 */
export function debounced(fn: () => void, ms: number) {
  let timer: number | undefined;
  const cancel = () => {
    if (timer === undefined) return;
    clearTimeout(timer);
    timer = undefined;
    counts.waiting--;
    publish();
  };
  const run = () => {
    cancel();
    counts.waiting++;
    publish();
    timer = window.setTimeout(() => {
      timer = undefined;
      counts.waiting--;
      try {
        fn();
      } finally {
        publish();
      }
    }, ms);
  };
  return Object.assign(run, { cancel });
}

// Read-only live views of the counters, and `idle()`.
const view: Record<string, unknown> = { idle };
for (const k of Object.keys(counts) as (keyof typeof counts)[]) {
  Object.defineProperty(view, k, { get: () => counts[k], enumerable: true });
}
(window as unknown as { __fiveaxis: unknown }).__fiveaxis = view;
