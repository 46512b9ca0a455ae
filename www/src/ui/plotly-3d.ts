// The 3D trace types the page draws, registered into the core of ./plotly-2d.ts.
import scatter3d from 'plotly.js/lib/scatter3d';
import surface from 'plotly.js/lib/surface';
import mesh3d from 'plotly.js/lib/mesh3d';
import cone from 'plotly.js/lib/cone';

export const traces3d = [scatter3d, surface, mesh3d, cone];
