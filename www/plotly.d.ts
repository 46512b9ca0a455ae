// Plotly's modular build (plotly.js/lib/core plus one module per trace type), typed as the
// whole of plotly.js for the core and as opaque modules for the traces.
declare module 'plotly.js/lib/core' {
  import * as Plotly from 'plotly.js';
  const core: typeof Plotly & { register(modules: unknown[]): void };
  export default core;
}
declare module 'plotly.js/lib/*' {
  const trace: unknown;
  export default trace;
}
