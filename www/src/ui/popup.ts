// Pop-up menus of the toolbar (a `details` whose body floats under its summary) kept within the
// screen: on a phone the summary may sit near the right edge.

/** Moves the body of pop-up `details` left as far as it would run off the right edge of the
 *  screen (never past the left one), each time it opens and when the window is resized. Its
 *  width is bounded by the screen in style.css. */
export function keepOnScreen(details: HTMLDetailsElement, margin = 8) {
  const place = () => {
    const body = details.querySelector<HTMLElement>(':scope > :not(summary)');
    if (!body || !details.open) return;
    body.style.left = '0px';
    const r = body.getBoundingClientRect();
    const over = r.right - (document.documentElement.clientWidth - margin);
    if (over > 0) body.style.left = `${-Math.min(over, Math.max(0, r.left - margin))}px`;
  };
  details.addEventListener('toggle', place);
  window.addEventListener('resize', place);
}
