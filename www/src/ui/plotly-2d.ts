// Plotly's core with only the 2D trace types the page draws (scatter is in the core): a bundle
// a quarter of Plotly's full one. The 3D types come in ./plotly-3d.ts, loaded when a 3D plot is
// about to be shown.
import Plotly from 'plotly.js/lib/core';
import bar from 'plotly.js/lib/bar';
import heatmap from 'plotly.js/lib/heatmap';
import scatterpolar from 'plotly.js/lib/scatterpolar';

Plotly.register([bar, heatmap, scatterpolar]);
export default Plotly;
