// A compass dial to set a range of forbidden driving directions (of a prohibited region, say).
// A range [from, to] runs clockwise from `from` to `to` in compass degrees (0 = north, 90 = east);
// it forbids the reverse directions too, so the dial fills both the sector and its opposite.
//
// An inline SVG with no stylesheet of its own: text and ticks in currentColor (day and night
// themes), the rim in var(--boundary), the sectors in var(--prohibited). Two handles on the rim set
// `from` and `to`, by dragging (mouse, pen or touch) or with the arrow keys when focused (Shift:
// steps of 10). The pure geometry (bearingFromPoint, normaliseDeg, sectorPath) is exported apart,
// to be tested without a DOM.

const SVG_NS = "http://www.w3.org/2000/svg";
const PROHIBITED = "var(--prohibited, #c8341c)";
const BOUNDARY = "var(--boundary, #161616)";
const HIT_RADIUS = 22; // an invisible circle around each handle: a 44 px touch target
const DOT_RADIUS = 8;
const LETTERS = { 0: "N", 90: "E", 180: "S", 270: "W" };
const KEY_STEPS = { ArrowRight: 1, ArrowUp: 1, ArrowLeft: -1, ArrowDown: -1, PageUp: 10, PageDown: -10 };

/** An angle in degrees brought into [0, 360); a value that is not a finite number gives 0. */
export function normaliseDeg(d) {
  if (!Number.isFinite(d)) return 0;
  const r = ((d % 360) + 360) % 360;
  return r === 360 || r === 0 ? 0 : r;
}

/**
 * The compass bearing in degrees, [0, 360), of screen point (x, y) seen from the centre (cx, cy):
 * screen y grows downwards and north is up, so up is 0, right 90, down 180 and left 270.
 * The centre itself gives 0.
 */
export function bearingFromPoint(cx, cy, x, y) {
  const dx = x - cx;
  const dy = cy - y;
  if (dx === 0 && dy === 0) return 0;
  return normaliseDeg((Math.atan2(dx, dy) * 180) / Math.PI);
}

/** A number for an SVG attribute: at most two decimals, no "-0". */
function num(v) {
  const r = Math.round(v * 100) / 100;
  return String(r === 0 ? 0 : r);
}

/** The screen point at compass bearing `deg` and distance `r` from (cx, cy). */
function polar(cx, cy, r, deg) {
  const a = (deg * Math.PI) / 180;
  return [cx + r * Math.sin(a), cy - r * Math.cos(a)];
}

/**
 * The SVG path data of the sector of radius `r` about (cx, cy) from bearing `from` clockwise to
 * `to` (compass degrees): "M centre L start A ... end Z". The span is (to - from) brought into
 * [0, 360), except that `to - from >= 360` is the full disc (two half arcs). A span of 0, or a
 * radius or argument that is not a positive / finite number, gives "".
 */
export function sectorPath(cx, cy, r, from, to) {
  if (![cx, cy, r, from, to].every(Number.isFinite) || !(r > 0)) return "";
  const full = to - from >= 360;
  const span = full ? 360 : normaliseDeg(to - from);
  if (span === 0) return "";
  if (full) {
    const [tx, ty] = polar(cx, cy, r, 0);
    const [bx, by] = polar(cx, cy, r, 180);
    const arc = (x, y) => `A ${num(r)} ${num(r)} 0 1 1 ${num(x)} ${num(y)}`;
    return `M ${num(tx)} ${num(ty)} ${arc(bx, by)} ${arc(tx, ty)} Z`;
  }
  const [x1, y1] = polar(cx, cy, r, from);
  const [x2, y2] = polar(cx, cy, r, from + span);
  const large = span > 180 ? 1 : 0;
  // Sweep flag 1: the positive-angle direction, which with y growing downwards is clockwise on screen.
  return `M ${num(cx)} ${num(cy)} L ${num(x1)} ${num(y1)} A ${num(r)} ${num(r)} 0 ${large} 1 ${num(x2)} ${num(y2)} Z`;
}

/** A whole compass degree in [0, 360). */
function wholeDeg(d) {
  return normaliseDeg(Math.round(normaliseDeg(d)));
}

/**
 * A dial in `container` to set one forbidden bearing range. `onChange({ from, to, final })` is called
 * when the user changes it: live while a handle is dragged (`final: false`), then once on release
 * (`final: true`); each key press calls it with `final: true`. `set` never calls it.
 */
export class BearingDial {
  /** Renders the dial (a `size` px square SVG) into `container`; the range starts as 0°–0°. */
  constructor(container, { onChange, size = 168, label = "Forbidden bearings" } = {}) {
    this.onChange = typeof onChange === "function" ? onChange : null;
    this.size = Number.isFinite(size) && size > 0 ? size : 168;
    this.from = 0;
    this.to = 0;
    this.drag = null; // { end: "from" | "to", pointerId } while a handle is dragged
    this.destroyed = false;

    const doc = container.ownerDocument;
    const el = (name, attrs = {}, parent = null) => {
      const node = doc.createElementNS(SVG_NS, name);
      // Inline style through the CSSOM: a style attribute is refused by the page's CSP.
      for (const [k, v] of Object.entries(attrs)) {
        if (k === "style") node.style.cssText = String(v);
        else node.setAttribute(k, String(v));
      }
      parent?.appendChild(node);
      return node;
    };
    const s = this.size;
    const c = s / 2;
    this.c = c;
    this.r = Math.max(8, c - HIT_RADIUS - 2); // the rim: the handles' hit circles stay inside the SVG

    const svg = el("svg", {
      xmlns: SVG_NS,
      viewBox: `0 0 ${s} ${s}`,
      width: s,
      height: s,
      role: "group",
      "aria-label": label,
      style: "touch-action: none; user-select: none; -webkit-user-select: none; overflow: visible",
    });
    this.svg = svg;

    const face = el("g", { "aria-hidden": "true" }, svg);
    el("circle", { cx: c, cy: c, r: this.r, fill: "none", stroke: BOUNDARY, "stroke-width": 1.5 }, face);
    const sectorAttrs = {
      fill: PROHIBITED,
      "fill-opacity": 0.35,
      stroke: PROHIBITED,
      "stroke-width": 1.5,
      "stroke-linejoin": "round",
    };
    this.sector = el("path", sectorAttrs, face);
    this.reverse = el("path", sectorAttrs, face);
    for (let deg = 0; deg < 360; deg += 30) {
      const major = deg % 90 === 0;
      const [x1, y1] = polar(c, c, this.r, deg);
      const [x2, y2] = polar(c, c, this.r - (major ? 9 : 5), deg);
      const tick = { x1: num(x1), y1: num(y1), x2: num(x2), y2: num(y2) };
      el("line", { ...tick, stroke: "currentColor", "stroke-width": major ? 1.5 : 1 }, face);
      if (major) {
        const [lx, ly] = polar(c, c, this.r - 18, deg);
        const letter = el("text", {
          x: num(lx),
          y: num(ly),
          fill: "currentColor",
          "font-size": 11,
          "font-weight": 600,
          "text-anchor": "middle",
          "dominant-baseline": "central",
        }, face);
        letter.textContent = LETTERS[deg];
      }
    }
    this.readout = el("text", {
      x: c,
      y: c,
      fill: "currentColor",
      "font-size": 13,
      "text-anchor": "middle",
      "dominant-baseline": "central",
    }, svg);

    this.handles = {};
    for (const end of ["from", "to"]) {
      const handle = el("g", {
        tabindex: 0,
        role: "slider",
        "aria-label": end === "from" ? "From bearing" : "To bearing",
        "aria-valuemin": 0,
        "aria-valuemax": 359,
        "aria-valuenow": 0,
        style: "cursor: grab; outline: none",
      }, svg);
      el("title", {}, handle).textContent = end === "from" ? "From bearing" : "To bearing";
      el("circle", { r: HIT_RADIUS, fill: "transparent", "pointer-events": "all" }, handle);
      const ring = el("circle", {
        r: DOT_RADIUS + 4,
        fill: "none",
        stroke: "currentColor",
        "stroke-width": 1.5,
        "stroke-dasharray": "3 2",
        visibility: "hidden",
      }, handle);
      // From: a filled dot; to: a ring, so that the two ends can be told apart.
      el("circle", {
        r: end === "from" ? DOT_RADIUS : DOT_RADIUS - 1.5,
        fill: end === "from" ? PROHIBITED : "none",
        stroke: end === "from" ? "currentColor" : PROHIBITED,
        "stroke-width": end === "from" ? 1.5 : 3,
        "pointer-events": "none",
      }, handle);
      handle.addEventListener("focus", () => ring.setAttribute("visibility", "visible"));
      handle.addEventListener("blur", () => ring.setAttribute("visibility", "hidden"));
      handle.addEventListener("pointerdown", (e) => this.pointerDown(e, end, handle));
      handle.addEventListener("pointermove", (e) => this.pointerMove(e));
      handle.addEventListener("pointerup", (e) => this.pointerEnd(e));
      handle.addEventListener("pointercancel", (e) => this.pointerEnd(e));
      handle.addEventListener("lostpointercapture", (e) => this.pointerEnd(e));
      handle.addEventListener("keydown", (e) => this.keyDown(e, end));
      this.handles[end] = handle;
    }

    container.appendChild(svg);
    this.render();
  }

  /**
   * Shows the range `from` → `to` (degrees, brought into whole degrees 0..359); an end that is not a
   * finite number stays as it is. Does not call onChange.
   */
  set(from, to) {
    if (Number.isFinite(from)) this.from = wholeDeg(from);
    if (Number.isFinite(to)) this.to = wholeDeg(to);
    this.render();
  }

  /** The range shown, `{ from, to }` in whole degrees 0..359. */
  get value() {
    return { from: this.from, to: this.to };
  }

  /** Removes the dial from the page; it calls onChange no more. */
  destroy() {
    this.destroyed = true;
    this.drag = null;
    this.svg.remove();
  }

  /** Draws the sectors, the handles and the numbers for the current range. */
  render() {
    const c = this.c;
    this.sector.setAttribute("d", sectorPath(c, c, this.r, this.from, this.to));
    this.reverse.setAttribute("d", sectorPath(c, c, this.r, this.from + 180, this.to + 180));
    this.readout.textContent = `${this.from}°–${this.to}°`;
    for (const end of ["from", "to"]) {
      const [x, y] = polar(c, c, this.r, this[end]);
      const handle = this.handles[end];
      handle.setAttribute("transform", `translate(${num(x)} ${num(y)})`);
      handle.setAttribute("aria-valuenow", String(this[end]));
      handle.setAttribute("aria-valuetext", `${this[end]} degrees`);
    }
  }

  /** Tells the owner about a change the user made. */
  changed(final) {
    if (!this.destroyed) this.onChange?.({ from: this.from, to: this.to, final });
  }

  /** Starts dragging end `end` of the range. */
  pointerDown(e, end, handle) {
    if (this.destroyed || (e.pointerType === "mouse" && e.button !== 0)) return;
    e.preventDefault();
    handle.focus?.({ preventScroll: true });
    try {
      handle.setPointerCapture(e.pointerId);
    } catch {
      // The pointer is gone already: no drag.
      return;
    }
    this.drag = { end, pointerId: e.pointerId };
    handle.style.cursor = "grabbing";
  }

  /** Moves the dragged end to the bearing of the pointer. */
  pointerMove(e) {
    const drag = this.drag;
    if (!drag || e.pointerId !== drag.pointerId) return;
    const box = this.svg.getBoundingClientRect();
    const bearing = bearingFromPoint(box.left + box.width / 2, box.top + box.height / 2, e.clientX, e.clientY);
    const deg = wholeDeg(bearing);
    if (deg === this[drag.end]) return;
    this[drag.end] = deg;
    this.render();
    this.changed(false);
  }

  /** Ends a drag (pointer up, cancelled or capture lost): the value is final. */
  pointerEnd(e) {
    const drag = this.drag;
    if (!drag || e.pointerId !== drag.pointerId) return;
    this.drag = null;
    const handle = this.handles[drag.end];
    handle.style.cursor = "grab";
    if (handle.hasPointerCapture?.(e.pointerId)) handle.releasePointerCapture(e.pointerId);
    this.changed(true);
  }

  /** Arrow keys turn the focused end by 1 degree (10 with Shift; PageUp / PageDown: 10). */
  keyDown(e, end) {
    const step = KEY_STEPS[e.key];
    if (this.destroyed || !step || e.altKey || e.ctrlKey || e.metaKey) return;
    e.preventDefault();
    this[end] = wholeDeg(this[end] + (e.shiftKey && Math.abs(step) === 1 ? step * 10 : step));
    this.render();
    this.changed(true);
  }
}
