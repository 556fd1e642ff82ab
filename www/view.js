// The map: a <canvas> that draws the field and its plan in local metres, HiDPI-aware, with pan
// (drag with mouse, pen or one finger), zoom (wheel or trackpad pinch about the cursor, two-finger
// pinch, double click, + / - keys and buttons) and fit.
//
// Over this, three optional layers that others own: `background` (an XYZ tile layer, tiles.js,
// drawn under the field), `tool` (the field editor, edit-tool.js: it takes the presses on its
// handles and taps, and draws its marks) and `overlay(ctx, view)` (the machine driving the path).
//
// Colours come from CSS custom properties (style.css) so that a night theme can swap them; the
// constants below are only the fallback when a property is missing.

/** CSS custom property of each theme colour, with its daylight fallback. */
export const THEME_VARS = {
  outside: ["--map-outside", "#e4e7de"],
  field: ["--map-field", "#fdfdfb"],
  boundary: ["--boundary", "#161616"],
  obstacleFill: ["--obstacle-fill", "#6f5641"],
  obstacleStroke: ["--obstacle-stroke", "#3b2a1b"],
  group: ["--obstacle-group", "#3b2a1b"],
  uncovered: ["--uncovered", "#6a1fd1"],
  classFill: ["--class-fill", "#3b2a1b"],
  classText: ["--class-text", "#ffffff"],
  prohibited: ["--prohibited", "#c8341c"],
  prohibitedFill: ["--prohibited-fill", "rgba(200, 52, 28, 0.10)"],
  blockStroke: ["--block-stroke", "#a3ab99"],
  block1: ["--block-1", "#e3f0d3"],
  block2: ["--block-2", "#fbedc8"],
  block3: ["--block-3", "#dbe8f5"],
  block4: ["--block-4", "#f5dde8"],
  block5: ["--block-5", "#e6e1f3"],
  block6: ["--block-6", "#d8efea"],
  headland: ["--headland", "#00875f"],
  swath: ["--swath", "#0061b0"],
  turn: ["--turn", "#e08600"],
  connection: ["--connection", "#c8007a"],
  start: ["--start", "#1e9e3a"],
  end: ["--end", "#161616"],
  label: ["--label-text", "#161616"],
  labelFill: ["--label-fill", "#ffffff"],
  marker: ["--error-mark", "#d0021b"],
  warnMark: ["--warn-mark", "#ffd23f"],
  warnEdge: ["--warn-edge", "#6b4e00"],
  scale: ["--scale-text", "#2b2f28"],
  select: ["--select", "#0a84ff"],
  entrance: ["--entrance", "#1e9e3a"],
  reference: ["--reference", "#7a3fb0"],
  machine: ["--machine", "#ff5a00"],
  way: ["--way", "#00a6c8"],
};

const BLOCK_KEYS = ["block1", "block2", "block3", "block4", "block5", "block6"];
const FONT = 'system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif';
const FIT_PADDING = 28; // CSS px around the field when fitting
const MAX_SCALE = 200; // px per metre
const TAP_PX = 6; // a press that moves less than this is a tap, not a pan or a drag
const TAP_MS = 600;
const BADGE_RADIUS = 14; // CSS px: the warning badges' pip (notes.js, style.css .pip) and a margin

/** Reads the theme colours from CSS custom properties of `el`. */
export function readTheme(el = document.documentElement) {
  const style = getComputedStyle(el);
  const theme = {};
  for (const [key, [name, fallback]] of Object.entries(THEME_VARS)) {
    theme[key] = style.getPropertyValue(name).trim() || fallback;
  }
  theme.blocks = BLOCK_KEYS.map((k) => theme[k]);
  return theme;
}

export class PlanView {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.field = null; // fieldScene()
    this.plan = null; // planScene()
    this.marker = null; // [x, y] in metres: the place an error points at
    this.keepClear = []; // [x, y] in metres: where badges lie over the map (labels keep clear)
    this.highlights = []; // [{ paths: [{ points, closed }], kind: "error" | "warning" }] in metres
    this.extraBounds = null; // [x0, y0, x1, y1]: more to fit than the field, e.g. an error's place
    this.machineWidth = 6; // metres, to scale line widths when zoomed far out
    this.cx = 0; // view centre, metres
    this.cy = 0;
    this.scale = 1; // CSS px per metre
    this.fitted = true; // the user has not moved the view since the last fit
    this.cssW = 0;
    this.cssH = 0;
    this.dpr = 1;
    this.pointers = new Map();
    this.frame = 0;
    this.theme = readTheme();
    this.hatch = null;
    this.onViewChange = null;
    this.background = null; // { draw(ctx, view, projection) }
    this.projection = null; // the field's, for the background
    this.tool = null; // { hit, drag, release, tap, doubleTap, hover, key, draw }
    this.toolDrag = null; // { id, target, moved, start }
    this.taps = new Map(); // pointer id -> where and when it went down, to tell taps from pans
    this.overlay = null; // (ctx, theme, view) => void, drawn last
    this.bottomInset = 0; // CSS px at the bottom that a bar covers: the scale bar keeps above
    this.fitInsets = null; // { top, right, bottom, left } CSS px of the map that buttons cover
    this.onDraw = null; // called after every frame, to move what lies over the canvas
    // What the last frame drew, for tests and debugging: the obstacle class labels in view
    // ({ text, index, x, y } in CSS px of the canvas), and the lifted stretches of swaths.
    this.drawn = { classLabels: [], liftedStretches: 0, uncovered: 0 };

    this.bindPointers();
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.watchPixelRatio();
    this.resize();
  }

  /** Re-reads the colours (after a theme change) and redraws. */
  refreshTheme() {
    this.theme = readTheme();
    this.hatch = null;
    this.draw();
  }

  /** Shows a field (fieldScene); fits the view to it when `fit` is true. `keepPlan`: the plan
   * drawn stays until the next (the field is being edited and re-planned). */
  setField(field, { fit = true, keepPlan = false } = {}) {
    this.field = field;
    if (keepPlan) {
      this.requestDraw(); // a drag moves the field many times a frame: one draw per frame
      return;
    }
    this.plan = null;
    this.marker = null;
    this.highlights = [];
    this.extraBounds = null;
    if (fit) this.fit();
    else this.draw();
  }

  /** Shows a plan (planScene) over the field, or none; `marker` marks a point (metres);
   * `keepClear` lists points (metres) where badges lie over the map, for labels to avoid. */
  setPlan(plan, { machineWidth, marker = null, keepClear = [] } = {}) {
    this.plan = plan;
    this.marker = marker;
    this.keepClear = keepClear.filter(Boolean);
    if (Number.isFinite(machineWidth) && machineWidth > 0) this.machineWidth = machineWidth;
    this.draw();
  }

  /** Outlines drawn over everything in the error or warning colour (see `highlights`). */
  setHighlights(highlights) {
    this.highlights = highlights ?? [];
    this.draw();
  }

  /** The view as plain data, for tests and debugging. */
  state() {
    return { cx: this.cx, cy: this.cy, scale: this.scale, fitted: this.fitted, width: this.cssW, height: this.cssH };
  }

  // ---- view transform ------------------------------------------------------------------------

  bounds() {
    const a = this.field?.bounds ?? null;
    const b = this.extraBounds;
    if (!a || !b) return a ?? b;
    return [Math.min(a[0], b[0]), Math.min(a[1], b[1]), Math.max(a[2], b[2]), Math.max(a[3], b[3])];
  }

  fit() {
    const b = this.bounds();
    this.fitted = true;
    if (b && this.cssW > 0 && this.cssH > 0) {
      const w = Math.max(b[2] - b[0], 1);
      const h = Math.max(b[3] - b[1], 1);
      const pad = Math.min(FIT_PADDING, this.cssW / 8, this.cssH / 8);
      // The free part of the map: without the buttons over its edges, where they leave most of it.
      let { top = 0, right = 0, bottom = 0, left = 0 } = this.fitInsets ?? {};
      if (left + right > this.cssW / 3) left = right = 0;
      if (top + bottom > this.cssH / 3) top = bottom = 0;
      const fw = this.cssW - 2 * pad - left - right;
      const fh = this.cssH - 2 * pad - top - bottom;
      this.scale = Math.min(fw / w, fh / h);
      const sx = left + pad + fw / 2; // the free part's centre on screen
      const sy = top + pad + fh / 2;
      this.cx = (b[0] + b[2]) / 2 - (sx - this.cssW / 2) / this.scale;
      this.cy = (b[1] + b[3]) / 2 + (sy - this.cssH / 2) / this.scale;
    }
    this.draw();
    this.changed();
  }

  minScale() {
    const b = this.bounds();
    if (!b || !this.cssW) return 1e-4;
    const size = Math.max(b[2] - b[0], b[3] - b[1], 1);
    return Math.min(this.cssW, this.cssH) / size / 20;
  }

  /** Zooms by `factor` keeping the point under screen position (sx, sy) in place. */
  zoomAt(factor, sx = this.cssW / 2, sy = this.cssH / 2) {
    this.moveTo(sx, sy, sx, sy, factor);
  }

  /** Zooms by `factor` and moves the world point under (sx0, sy0) to (sx1, sy1). */
  moveTo(sx0, sy0, sx1, sy1, factor = 1) {
    const [wx, wy] = this.toWorld(sx0, sy0);
    const s = Math.min(MAX_SCALE, Math.max(this.minScale(), this.scale * factor));
    this.scale = s;
    this.cx = wx - (sx1 - this.cssW / 2) / s;
    this.cy = wy + (sy1 - this.cssH / 2) / s;
    this.fitted = false;
    this.requestDraw();
    this.changed();
  }

  toWorld(sx, sy) {
    return [this.cx + (sx - this.cssW / 2) / this.scale, this.cy - (sy - this.cssH / 2) / this.scale];
  }

  changed() {
    this.onViewChange?.(this.state());
  }

  // ---- size ----------------------------------------------------------------------------------

  resize() {
    const w = this.canvas.clientWidth;
    const h = this.canvas.clientHeight;
    const dpr = window.devicePixelRatio || 1;
    if (w === this.cssW && h === this.cssH && dpr === this.dpr) return;
    this.cssW = w;
    this.cssH = h;
    this.dpr = dpr;
    this.canvas.width = Math.max(1, Math.round(w * dpr));
    this.canvas.height = Math.max(1, Math.round(h * dpr));
    this.hatch = null;
    if (this.fitted) this.fit();
    else this.draw();
  }

  /** Redraws sharply when the page moves to a screen of another pixel ratio (or browser zoom). */
  watchPixelRatio() {
    const watch = () => {
      const mq = matchMedia(`(resolution: ${window.devicePixelRatio || 1}dppx)`);
      mq.addEventListener(
        "change",
        () => {
          this.resize();
          watch();
        },
        { once: true },
      );
    };
    watch();
  }

  // ---- input ---------------------------------------------------------------------------------

  bindPointers() {
    const c = this.canvas;
    const at = (e) => {
      const r = c.getBoundingClientRect();
      return { x: e.clientX - r.left, y: e.clientY - r.top };
    };
    c.addEventListener("pointerdown", (e) => {
      if (e.pointerType === "mouse" && e.button !== 0) return;
      c.setPointerCapture(e.pointerId);
      const p = at(e);
      e.preventDefault();
      c.focus({ preventScroll: true });
      if (this.toolDrag) {
        // A second finger while a handle is dragged: the drag ends, the fingers pan and pinch.
        this.endToolDrag(this.toolDrag.start);
      } else if (this.pointers.size === 0) {
        const target = this.tool?.hit(p, e);
        if (target) {
          this.toolDrag = { id: e.pointerId, target, moved: false, start: p };
          c.classList.add("dragging-handle");
          return;
        }
      }
      // A second finger makes every press a pinch, not a tap.
      const multi = this.pointers.size > 0;
      if (multi) for (const tap of this.taps.values()) tap.multi = true;
      this.taps.set(e.pointerId, { x: p.x, y: p.y, t: performance.now(), multi });
      this.pointers.set(e.pointerId, p);
      c.classList.add("dragging");
    });
    c.addEventListener("pointermove", (e) => {
      const p = at(e);
      const drag = this.toolDrag;
      if (drag && drag.id === e.pointerId) {
        if (!drag.moved && Math.hypot(p.x - drag.start.x, p.y - drag.start.y) < TAP_PX) return;
        drag.moved = true;
        this.tool.drag(drag.target, p, e);
        return;
      }
      if (!this.pointers.has(e.pointerId)) {
        if (this.pointers.size === 0 && e.pointerType === "mouse") this.tool?.hover?.(p, e);
        return;
      }
      const before = this.gesture();
      this.pointers.set(e.pointerId, p);
      const after = this.gesture();
      const ratio = before.dist > 0 && after.dist > 0 ? after.dist / before.dist : 1;
      this.moveTo(before.x, before.y, after.x, after.y, ratio);
    });
    const up = (e) => {
      if (this.toolDrag?.id === e.pointerId) {
        this.endToolDrag(at(e));
        return;
      }
      const tap = this.taps.get(e.pointerId);
      this.taps.delete(e.pointerId);
      const wasPointer = this.pointers.delete(e.pointerId);
      if (this.pointers.size === 0) c.classList.remove("dragging");
      if (e.type !== "pointerup" || !wasPointer || !tap || tap.multi) return;
      const p = at(e);
      if (Math.hypot(p.x - tap.x, p.y - tap.y) < TAP_PX && performance.now() - tap.t < TAP_MS) this.tool?.tap(p, e);
    };
    c.addEventListener("pointerup", up);
    c.addEventListener("pointercancel", up);
    c.addEventListener("lostpointercapture", up);
    c.addEventListener(
      "wheel",
      (e) => {
        e.preventDefault();
        const unit = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? this.cssH : 1;
        // Trackpad pinch arrives as a wheel event with ctrlKey and small deltas.
        const k = e.ctrlKey ? 0.01 : 0.0015;
        const { x, y } = at(e);
        this.zoomAt(Math.exp(-e.deltaY * unit * k), x, y);
      },
      { passive: false },
    );
    c.addEventListener("dblclick", (e) => {
      const { x, y } = at(e);
      if (this.tool?.doubleTap({ x, y }, e)) return;
      this.zoomAt(e.shiftKey ? 0.5 : 2, x, y);
    });
    c.addEventListener("keydown", (e) => {
      if (this.tool?.key(e)) {
        e.preventDefault();
        return;
      }
      const step = 0.15 * Math.min(this.cssW, this.cssH);
      const w = this.cssW / 2;
      const h = this.cssH / 2;
      const keys = {
        "+": () => this.zoomAt(1.5),
        "=": () => this.zoomAt(1.5),
        "-": () => this.zoomAt(1 / 1.5),
        0: () => this.fit(),
        f: () => this.fit(),
        ArrowLeft: () => this.moveTo(w, h, w + step, h),
        ArrowRight: () => this.moveTo(w, h, w - step, h),
        ArrowUp: () => this.moveTo(w, h, w, h + step),
        ArrowDown: () => this.moveTo(w, h, w, h - step),
      };
      const action = keys[e.key];
      if (action && !e.ctrlKey && !e.metaKey && !e.altKey) {
        action();
        e.preventDefault();
      }
    });
  }

  /** The press on a tool's handle ends at `p` (CSS px). */
  endToolDrag(p) {
    const drag = this.toolDrag;
    this.toolDrag = null;
    this.canvas.classList.remove("dragging-handle");
    if (drag) this.tool?.release(drag.target, p, drag.moved);
  }

  /** Midpoint and spread of the (first two) active pointers. */
  gesture() {
    const pts = [...this.pointers.values()].slice(0, 2);
    if (pts.length === 0) return { x: 0, y: 0, dist: 0 };
    if (pts.length === 1) return { x: pts[0].x, y: pts[0].y, dist: 0 };
    const [a, b] = pts;
    return { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2, dist: Math.hypot(a.x - b.x, a.y - b.y) };
  }

  // ---- drawing -------------------------------------------------------------------------------

  requestDraw() {
    if (this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.draw();
    });
  }

  draw() {
    if (this.frame) {
      cancelAnimationFrame(this.frame);
      this.frame = 0;
    }
    const { ctx, theme: t } = this;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = t.outside;
    ctx.fillRect(0, 0, this.canvas.width, this.canvas.height);
    ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
    ctx.lineJoin = "round";
    ctx.lineCap = "round";
    this.drawn = { classLabels: [], liftedStretches: 0, tiles: 0, uncovered: 0 };

    const field = this.field;
    const plan = this.plan;
    if (this.background && this.projection) this.drawn.tiles = this.background.draw(ctx, this, this.projection);
    if (field?.boundary) {
      this.polygonPath(field.boundary);
      ctx.fillStyle = t.field;
      ctx.fill("evenodd");
    }
    if (plan) this.drawBlocks(plan.blocks);
    if (field) this.drawProhibited(field.prohibited);
    if (field) {
      for (const obstacle of field.obstacles) {
        this.polygonPath(obstacle);
        ctx.fillStyle = t.obstacleFill;
        ctx.fill("evenodd");
        ctx.lineWidth = 1.5;
        ctx.strokeStyle = t.obstacleStroke;
        ctx.stroke();
      }
    }
    if (plan) this.drawGroups(plan.groups ?? []);
    if (plan) this.drawUncovered(plan.uncovered ?? []);
    if (field?.boundary) {
      this.polygonPath(field.boundary);
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = t.boundary;
      ctx.stroke();
    }
    if (plan) this.drawPaths(plan);
    this.drawHighlights();
    this.tool?.draw(ctx, t, this);
    this.overlay?.(ctx, t, this);
    if (this.marker) this.drawMarker(this.marker);
    this.drawScaleBar();
    this.onDraw?.();
  }

  /** The outlines an error (red, solid, on a white halo) or an open warning (dark dashes on a
   * yellow glow) concerns. */
  drawHighlights() {
    const { ctx, theme: t } = this;
    for (const { paths, kind } of this.highlights) {
      const error = kind === "error";
      ctx.beginPath();
      for (const path of paths) {
        const pts = path.points.filter(Boolean);
        if (pts.length === 1) {
          const [x, y] = this.toScreen(pts[0]);
          ctx.moveTo(x + 6, y);
          ctx.arc(x, y, 6, 0, 2 * Math.PI);
          continue;
        }
        this.linePath(pts);
        if (path.closed) ctx.closePath();
      }
      ctx.setLineDash([]);
      ctx.lineWidth = error ? 7 : 9;
      ctx.strokeStyle = error ? t.labelFill : t.warnMark;
      ctx.stroke();
      if (!error) ctx.setLineDash([7, 5]);
      ctx.lineWidth = error ? 3.5 : 2.5;
      ctx.strokeStyle = error ? t.marker : t.warnEdge;
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }

  /** Line width of the driven paths: thinner when the swaths crowd together on screen. */
  pathWidth() {
    const spacing = this.machineWidth * this.scale;
    return Math.min(2.5, Math.max(0.75, spacing * 0.3));
  }

  drawBlocks(blocks) {
    const { ctx, theme: t } = this;
    for (const block of blocks) {
      const i = block.order ?? block.index ?? 0;
      this.polygonPath(block.rings);
      ctx.fillStyle = t.blocks[i % t.blocks.length];
      ctx.fill("evenodd");
      ctx.lineWidth = 1;
      ctx.strokeStyle = t.blockStroke;
      ctx.stroke();
    }
  }

  /** The convex hulls class-C obstacles were merged into: a dashed outline on a light halo. */
  drawGroups(groups) {
    const { ctx, theme: t } = this;
    for (const group of groups) {
      this.polygonPath(group.rings);
      ctx.setLineDash([]);
      ctx.lineWidth = 4;
      ctx.strokeStyle = t.labelFill;
      ctx.globalAlpha = 0.7;
      ctx.stroke();
      ctx.globalAlpha = 1;
      ctx.setLineDash([7, 5]);
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.group;
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }

  /** The crop the plan leaves standing: red, dashed where the implement could not reach it. */
  drawUncovered(parts) {
    const { ctx, theme: t } = this;
    this.drawn.uncovered = parts.length;
    for (const part of parts) {
      this.polygonPath(part.rings);
      const reachable = (part.reachable_m2 ?? 0) > 0.5 * (part.area_m2 ?? 0);
      ctx.fillStyle = t.uncovered;
      ctx.globalAlpha = reachable ? 0.35 : 0.15;
      ctx.fill("evenodd");
      ctx.globalAlpha = 1;
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.uncovered;
      ctx.setLineDash(reachable ? [] : [4, 3]);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }

  drawProhibited(regions) {
    const { ctx, theme: t } = this;
    if (!regions.length) return;
    const hatch = this.hatchPattern();
    for (const region of regions) {
      this.polygonPath(region);
      ctx.fillStyle = t.prohibitedFill;
      ctx.fill("evenodd");
      if (hatch) {
        ctx.fillStyle = hatch;
        ctx.fill("evenodd");
      }
      ctx.setLineDash([6, 4]);
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.prohibited;
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }

  /** Diagonal hatching in the prohibited colour, drawn at device resolution. */
  hatchPattern() {
    if (this.hatch) return this.hatch;
    const size = Math.round(10 * this.dpr);
    const tile = document.createElement("canvas");
    tile.width = tile.height = size;
    const g = tile.getContext("2d");
    g.strokeStyle = this.theme.prohibited;
    g.globalAlpha = 0.55;
    g.lineWidth = 1.25 * this.dpr;
    g.beginPath();
    for (const o of [-size, 0, size]) {
      g.moveTo(o, size);
      g.lineTo(o + size, 0);
    }
    g.stroke();
    const pattern = this.ctx.createPattern(tile, "repeat");
    pattern?.setTransform?.(new DOMMatrix([1 / this.dpr, 0, 0, 1 / this.dpr, 0, 0]));
    this.hatch = pattern;
    return pattern;
  }

  drawPaths(plan) {
    const { ctx, theme: t } = this;
    const lw = this.pathWidth();
    const stroke = (lines, color, width, dash = []) => {
      if (!lines.length) return;
      ctx.beginPath();
      for (const line of lines) {
        this.linePath(line.points ?? line);
        if (line.closed) ctx.closePath();
      }
      ctx.setLineDash(dash);
      ctx.lineWidth = width;
      ctx.strokeStyle = color;
      ctx.stroke();
      ctx.setLineDash([]);
    };
    // A headland pass is a closed loop, or (along only the edges that need it) an open line.
    // Where the implement is lifted on a pass or swath, a gap with a thin dotted line and a tick
    // at each end.
    const headland = plan.paths.headland.flatMap((seg) =>
      seg.worked
        ? seg.worked.map((points) => ({ points, closed: false }))
        : [{ points: seg.points, closed: seg.props.closed === true }],
    );
    stroke(headland, t.headland, lw);
    const worked = plan.paths.swath.flatMap((seg) => seg.worked ?? [seg.points]);
    stroke(worked, t.swath, lw);
    this.drawn.liftedStretches =
      this.drawLifted(plan.paths.headland, t.headland, lw) + this.drawLifted(plan.paths.swath, t.swath, lw);
    stroke(plan.paths.turn, t.turn, lw * 0.9);
    ctx.lineCap = "butt";
    stroke(plan.paths.connection, t.connection, lw + 0.5, [8, 5]);
    ctx.lineCap = "round";
    this.drawArrows(plan.paths.swath, t.swath, lw);
    this.drawEnds(plan);
    const blockLabels = this.drawBlockLabels(plan.blocks);
    this.drawClassLabels(plan.obstacles ?? [], blockLabels);
  }

  /**
   * The stretches of swaths or passes where the implement is lifted (over a class-A obstacle,
   * or where it would reach out of the field); returns how many were drawn.
   */
  drawLifted(segments, color, lw) {
    const { ctx } = this;
    const stretches = segments.flatMap((seg) => seg.lifted ?? []);
    if (!stretches.length) return 0;
    const tick = Math.max(4, lw * 2.5);
    ctx.beginPath();
    for (const pts of stretches) this.linePath(pts);
    ctx.setLineDash([Math.max(1.5, lw * 0.6), Math.max(3, lw * 1.6)]);
    ctx.lineWidth = Math.max(1, lw * 0.6);
    ctx.strokeStyle = color;
    ctx.lineCap = "butt";
    ctx.stroke();
    ctx.setLineDash([]);
    // Where the implement is raised and lowered again: a short bar across the swath.
    ctx.beginPath();
    for (const pts of stretches) {
      const a = this.toScreen(pts[0]);
      const b = this.toScreen(pts[pts.length - 1]);
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      const dir = len > 1e-6 ? [(b[0] - a[0]) / len, (b[1] - a[1]) / len] : this.directionOf(pts);
      const n = [-dir[1] * tick, dir[0] * tick];
      for (const [x, y] of [a, b]) {
        ctx.moveTo(x - n[0], y - n[1]);
        ctx.lineTo(x + n[0], y + n[1]);
      }
    }
    ctx.lineWidth = Math.max(1.25, lw * 0.8);
    ctx.stroke();
    ctx.lineCap = "round";
    return stretches.length;
  }

  /** Unit direction (screen) of a line from its first to its last distinct point, or east. */
  directionOf(pts) {
    const a = this.toScreen(pts[0]);
    for (let i = pts.length - 1; i > 0; i--) {
      const b = this.toScreen(pts[i]);
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (len > 1e-6) return [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    }
    return [1, 0];
  }

  /** Chevrons in the middle of each swath, pointing the way it is driven, when there is room. */
  drawArrows(swaths, color, lw) {
    const spacing = this.machineWidth * this.scale;
    if (spacing < 12) return;
    const { ctx } = this;
    const size = Math.min(7, spacing * 0.3);
    ctx.beginPath();
    for (const seg of swaths) {
      const a = this.toScreen(seg.points[0]);
      const b = this.toScreen(seg.points[seg.points.length - 1]);
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (len < 6 * size) continue;
      const ux = (b[0] - a[0]) / len;
      const uy = (b[1] - a[1]) / len;
      const mx = (a[0] + b[0]) / 2 + ux * size * 0.5;
      const my = (a[1] + b[1]) / 2 + uy * size * 0.5;
      ctx.moveTo(mx - ux * size - uy * size * 0.8, my - uy * size + ux * size * 0.8);
      ctx.lineTo(mx, my);
      ctx.lineTo(mx - ux * size + uy * size * 0.8, my - uy * size - ux * size * 0.8);
    }
    ctx.lineWidth = Math.max(1.25, lw);
    ctx.strokeStyle = color;
    ctx.stroke();
  }

  /** Start (round) and end (square) of the route. */
  drawEnds(plan) {
    const { ctx, theme: t } = this;
    if (plan.end) {
      const [x, y] = this.toScreen(plan.end);
      ctx.beginPath();
      ctx.rect(x - 5.5, y - 5.5, 11, 11);
      ctx.fillStyle = t.end;
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
    }
    if (plan.start) {
      const [x, y] = this.toScreen(plan.start);
      ctx.beginPath();
      ctx.arc(x, y, 7, 0, 2 * Math.PI);
      ctx.fillStyle = t.start;
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
    }
  }

  /** The order in which blocks are worked, counted from 1, in a disc at each block's centre;
   * a label that would cover another is left out. */
  drawBlockLabels(blocks) {
    const { ctx, theme: t } = this;
    const placed = [];
    const r = 11;
    ctx.font = `700 13px ${FONT}`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    const sorted = [...blocks].sort((a, b) => (a.order ?? 0) - (b.order ?? 0));
    const boxes = [];
    for (const block of sorted) {
      if (block.order == null) continue;
      const [x, y] = this.toScreen(block.label);
      if (x < -r || y < -r || x > this.cssW + r || y > this.cssH + r) continue;
      if (placed.some(([px, py]) => Math.hypot(px - x, py - y) < 2 * r + 2)) continue;
      placed.push([x, y]);
      const text = String(block.order + 1);
      const w = Math.max(2 * r, ctx.measureText(text).width + 10);
      boxes.push({ x0: x - w / 2, y0: y - r, x1: x + w / 2, y1: y + r });
      ctx.beginPath();
      ctx.roundRect(x - w / 2, y - r, w, 2 * r, r);
      ctx.fillStyle = t.labelFill;
      ctx.fill();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.label;
      ctx.stroke();
      ctx.fillStyle = t.label;
      ctx.fillText(text, x, y + 0.5);
    }
    return boxes;
  }

  /**
   * The class of each obstacle (A-D) in a small dark tag: on the obstacle when it is large
   * enough on screen, else beside it (below first: a warning badge sits on its top edge), where
   * it covers no other tag, block label or badge (`keepClear`). `avoid`: boxes already taken,
   * in CSS px.
   */
  drawClassLabels(obstacles, avoid = []) {
    const { ctx, theme: t } = this;
    const h = 16;
    ctx.font = `800 11px ${FONT}`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    const badge = BADGE_RADIUS;
    const taken = [
      ...avoid,
      ...this.keepClear.map((p) => {
        const [x, y] = this.toScreen(p);
        return { x0: x - badge, y0: y - badge, x1: x + badge, y1: y + badge };
      }),
    ];
    // How much of box b lies on boxes already taken (2 px apart at least), in px².
    const overlap = (b) =>
      taken.reduce(
        (sum, o) =>
          sum +
          Math.max(0, Math.min(b.x1, o.x1 + 2) - Math.max(b.x0, o.x0 - 2)) *
            Math.max(0, Math.min(b.y1, o.y1 + 2) - Math.max(b.y0, o.y0 - 2)),
        0,
      );
    for (const o of obstacles) {
      if (!o.class) continue;
      const text = String(o.class);
      const w = Math.max(h, ctx.measureText(text).width + 8);
      let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
      for (const p of o.rings[0]) {
        const [x, y] = this.toScreen(p);
        x0 = Math.min(x0, x);
        y0 = Math.min(y0, y);
        x1 = Math.max(x1, x);
        y1 = Math.max(y1, y);
      }
      if (x1 < -w || y1 < -h || x0 > this.cssW + w || y0 > this.cssH + h) continue;
      const mx = (x0 + x1) / 2;
      const my = (y0 + y1) / 2;
      const candidates = [];
      if (x1 - x0 >= w + 8 && y1 - y0 >= h + 8) candidates.push(this.toScreen(o.label));
      // Beside it, close, then a little further out (past a badge on it).
      for (const gap of [3, badge + 4]) {
        candidates.push(
          [mx, y1 + gap + h / 2],
          [x1 + gap + w / 2, my],
          [x0 - gap - w / 2, my],
          [mx, y0 - gap - h / 2],
          [x1 + gap + w / 2, y1 + gap + h / 2],
          [x0 - gap - w / 2, y1 + gap + h / 2],
        );
      }
      const box = ([x, y]) => ({ x0: x - w / 2, y0: y - h / 2, x1: x + w / 2, y1: y + h / 2 });
      let best = null;
      for (const c of candidates) {
        const cost = overlap(box(c));
        if (!best || cost < best.cost) best = { c, cost };
        if (cost === 0) break;
      }
      const [x, y] = best.c;
      taken.push(box([x, y]));
      ctx.beginPath();
      ctx.roundRect(x - w / 2, y - h / 2, w, h, 4);
      ctx.fillStyle = t.classFill;
      ctx.fill();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
      ctx.fillStyle = t.classText;
      ctx.fillText(text, x, y + 0.5);
      if (x >= 0 && y >= 0 && x <= this.cssW && y <= this.cssH) this.drawn.classLabels.push({ text, index: o.index, x, y });
    }
  }

  /** A ring and cross at the place an error points at. */
  drawMarker(p) {
    const { ctx, theme: t } = this;
    const [x, y] = this.toScreen(p);
    ctx.beginPath();
    ctx.arc(x, y, 12, 0, 2 * Math.PI);
    ctx.moveTo(x - 18, y);
    ctx.lineTo(x + 18, y);
    ctx.moveTo(x, y - 18);
    ctx.lineTo(x, y + 18);
    ctx.lineWidth = 3;
    ctx.strokeStyle = t.labelFill;
    ctx.stroke();
    ctx.lineWidth = 2;
    ctx.strokeStyle = t.marker;
    ctx.stroke();
  }

  /** A scale bar of a round length and a north arrow, bottom left. */
  drawScaleBar() {
    if (!this.cssW || !this.scale) return;
    const { ctx, theme: t } = this;
    const target = Math.min(140, this.cssW / 4) / this.scale; // metres
    const pow = 10 ** Math.floor(Math.log10(target));
    const metres = [5, 2, 1].map((m) => m * pow).find((m) => m <= target) ?? pow;
    const px = metres * this.scale;
    const x = 14;
    const y = this.cssH - 16 - this.bottomInset;
    const label = metres >= 1000 ? `${metres / 1000} km` : `${+metres.toPrecision(3)} m`;
    ctx.font = `600 12px ${FONT}`;
    ctx.textAlign = "left";
    ctx.textBaseline = "bottom";
    ctx.lineCap = "butt";
    for (const [color, width] of [
      [t.labelFill, 5],
      [t.scale, 2],
    ]) {
      ctx.beginPath();
      ctx.moveTo(x, y - 6);
      ctx.lineTo(x, y);
      ctx.lineTo(x + px, y);
      ctx.lineTo(x + px, y - 6);
      ctx.lineWidth = width;
      ctx.strokeStyle = color;
      ctx.stroke();
    }
    ctx.lineWidth = 3;
    ctx.strokeStyle = t.labelFill;
    ctx.strokeText(label, x + 4, y - 4);
    ctx.fillStyle = t.scale;
    ctx.fillText(label, x + 4, y - 4);
    // North arrow above the scale bar.
    const nx = x + 8;
    const ny = y - 30;
    ctx.beginPath();
    ctx.moveTo(nx, ny - 12);
    ctx.lineTo(nx + 6, ny + 4);
    ctx.lineTo(nx, ny);
    ctx.lineTo(nx - 6, ny + 4);
    ctx.closePath();
    ctx.fillStyle = t.scale;
    ctx.lineWidth = 2;
    ctx.strokeStyle = t.labelFill;
    ctx.stroke();
    ctx.fill();
    ctx.textAlign = "left";
    ctx.textBaseline = "middle";
    ctx.lineWidth = 3;
    ctx.strokeText("N", nx + 9, ny - 5);
    ctx.fillText("N", nx + 9, ny - 5);
    ctx.lineCap = "round";
  }

  toScreen([x, y]) {
    return [this.cssW / 2 + (x - this.cx) * this.scale, this.cssH / 2 - (y - this.cy) * this.scale];
  }

  polygonPath(rings) {
    this.ctx.beginPath();
    for (const ring of rings) {
      this.linePath(ring);
      this.ctx.closePath();
    }
  }

  linePath(points) {
    const { ctx } = this;
    for (let i = 0; i < points.length; i++) {
      const [x, y] = this.toScreen(points[i]);
      if (i === 0) ctx.moveTo(x, y);
      else ctx.lineTo(x, y);
    }
  }
}
