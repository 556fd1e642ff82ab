// The edit hint ("Field: tap its corners…") over the map, placed where it covers none of the
// marks the user presses or is putting down: above the edit bar on the right, else on the left,
// else at the top left. It is placed again after every frame the view draws (the marks move as
// the map pans and zooms, and as corners are tapped).

const MARGIN = 10; // CSS px from the map's edges
const MAX_WIDTH = 520; // CSS px
const CLEAR = 14; // CSS px: a mark this near the hint (a handle's radius and a finger's) is under it

export class EditHint {
  /**
   * @param {HTMLElement} el the hint, absolutely positioned in the map section
   * @param {object} o
   * @param {import("./view.js").PlanView} o.view its cssW, cssH and bottomInset (the edit bar)
   * @param {HTMLElement[]} o.avoid elements over the map the hint must not cover (the map's
   *   buttons, the error callout when shown)
   */
  constructor(el, { view, avoid }) {
    this.el = el;
    this.view = view;
    this.avoid = avoid;
    this.text = "";
    this.sizes = new Map(); // max width -> [w, h] of the text shown
    this.width = 0; // the map's width the sizes are for
    this.at = "bottom-right"; // where it is: bottom-right, bottom-left or top-left
  }

  /** Shows `text` (empty: hides the hint) and places it clear of `points`. */
  show(text, points = []) {
    text = text ?? "";
    this.el.hidden = !text;
    if (text !== this.text) {
      this.text = text;
      this.el.textContent = text;
      this.sizes.clear();
    }
    this.layout(points);
  }

  /** The hint's size [w, h] at most `maxWidth` wide (measured once per text and width). */
  measure(maxWidth) {
    const key = Math.round(maxWidth);
    if (!this.sizes.has(key)) {
      Object.assign(this.el.style, { left: "0px", top: "0px", maxWidth: `${key}px` });
      this.sizes.set(key, [this.el.offsetWidth, this.el.offsetHeight]);
    }
    return [this.sizes.get(key)[0], this.sizes.get(key)[1], key];
  }

  /** The boxes of the elements to keep clear of, in CSS px of the map. */
  blocked() {
    const box = this.el.offsetParent?.getBoundingClientRect();
    if (!box) return [];
    return this.avoid
      .filter((e) => e && !e.hidden && e.offsetParent)
      .map((e) => {
        const r = e.getBoundingClientRect();
        return [r.left - box.left, r.top - box.top, r.right - box.left, r.bottom - box.top];
      });
  }

  /** Places the hint clear of `points` ([x, y] in CSS px of the map). */
  layout(points) {
    if (this.el.hidden || !this.view.cssW) return;
    const W = this.view.cssW;
    const H = this.view.cssH;
    if (W !== this.width) {
      this.width = W;
      this.sizes.clear();
    }
    const blocked = this.blocked();
    // At the bottom, above the edit bar, as wide as it likes; at the top, left of the map's
    // buttons (the boxes in the right half), narrower and taller.
    const wide = this.measure(Math.min(MAX_WIDTH, W - 2 * MARGIN));
    const buttons = Math.min(W, ...blocked.filter(([x0]) => x0 > W / 2).map(([x0]) => x0));
    const narrow = this.measure(Math.max(120, Math.min(MAX_WIDTH, buttons - 2 * MARGIN)));
    const above = H - (this.view.bottomInset || 0) - 8;
    const candidates = [
      ["bottom-right", W - MARGIN - wide[0], above - wide[1], wide],
      ["bottom-left", MARGIN, above - wide[1], wide],
      ["top-left", MARGIN, MARGIN, narrow],
    ];
    let best = null;
    for (const [name, x, y, [w, h, maxWidth]] of candidates) {
      const covered = points.filter(([px, py]) => px > x - CLEAR && px < x + w + CLEAR && py > y - CLEAR && py < y + h + CLEAR).length;
      const overlaps = blocked.some(([x0, y0, x1, y1]) => x < x1 && x + w > x0 && y < y1 && y + h > y0);
      const score = covered + (overlaps ? 1e6 : 0);
      if (!best || score < best.score) best = { name, x, y, maxWidth, score };
      if (score === 0) break;
    }
    this.at = best.name;
    this.el.dataset.place = best.name;
    Object.assign(this.el.style, {
      left: `${Math.round(best.x)}px`,
      top: `${Math.round(Math.max(MARGIN, best.y))}px`,
      maxWidth: `${best.maxWidth}px`,
    });
  }
}
