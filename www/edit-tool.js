// Editing the field on the map, by mouse, pen or touch. The view (view.js) hands the tool its
// pointer events: `hit` on a press (a handle the tool takes, or null to pan), `drag` and `release`
// for a handle, `tap` for a press that did not move, `doubleTap`, `hover`, and `draw` for the
// tool's own marks over the map.
//
// Modes:
//   view        pan and zoom only (nothing on the map moves by accident)
//   edit        drag a vertex; drag or tap the small mark in the middle of an edge to put a vertex
//               there; tap a vertex or a region to select it (Delete removes it); drag the
//               entrance or the ends of the AB line
//   boundary, obstacle, prohibited
//               tap the corners one by one; tap the first again, double-tap, or Finish to close
//   entrance    tap where the machine enters the field
//   abline      tap A, then B: the swaths run along the line from A to B
//   edge        tap the boundary edge the swaths should run along
//   parcel      a file of many parcels (a register's export): taps go to `onParcelTap` (parcels.js
//               draws them and picks the one tapped)
//   way         the way out along the tracks: taps go to `onWayTap` (way.js asks the planner)
//
// Every change goes through the History (editor.js) and `onChange(doc, { final })`: `final` is
// false while a vertex is dragged (plan it, do not keep it as a step yet) and true once it is a step.
import {
  addPolygon,
  deleteFeature,
  deleteVertex,
  editableRings,
  entranceOf,
  insertVertex,
  moveVertex,
  referenceLineOf,
  roleOf,
  setEntrance,
  setReferenceLine,
} from "./editor.js";
import { insidePolygon } from "./scene.js";

export const MODES = ["view", "edit", "boundary", "obstacle", "prohibited", "entrance", "abline", "edge", "parcel", "way"];
const DRAW_MODES = new Set(["boundary", "obstacle", "prohibited"]);
const HIT_PX = 22; // half of a 44 px touch target
const MID_MIN_PX = 40; // an edge shorter on screen than this has no insert mark
/** The forbidden range a new prohibited region starts with: the user sets it next. */
export const DEFAULT_FORBIDDEN = [[0, 30]];

export class EditTool {
  /**
   * @param {object} o
   * @param {import("./view.js").PlanView} o.view
   * @param {() => {forward: Function, inverse: Function} | null} o.projection the field's projection
   * @param {import("./editor.js").History} o.history
   * @param {(doc, info: {final: boolean}) => void} o.onChange
   * @param {() => void} [o.onState] mode, selection or draft changed
   * @param {(edge: number) => void} [o.onPickEdge]
   * @param {(line) => void} [o.onPickLine]
   * @param {(pt: {x: number, y: number}) => void} [o.onParcelTap] a tap in parcel mode (screen px)
   * @param {(world: number[]) => void} [o.onWayTap]
   */
  constructor({ view, projection, history, onChange, onState, onPickEdge, onPickLine, onParcelTap, onWayTap }) {
    this.view = view;
    this.projection = projection;
    this.history = history;
    this.onChange = onChange;
    this.onState = onState ?? (() => {});
    this.onPickEdge = onPickEdge ?? (() => {});
    this.onPickLine = onPickLine ?? (() => {});
    this.onParcelTap = onParcelTap ?? (() => {});
    this.onWayTap = onWayTap ?? (() => {});
    this.mode = "view";
    this.selection = null; // { feature, part, ring, vertex } (vertex null: the whole feature)
    this.draft = []; // world points of the polygon or line being drawn
    this.hoverPoint = null; // world point under a hovering mouse, for the draft's rubber band
    this.dragging = null; // the handle being dragged, with the document it started from
    this.cache = { doc: null, projection: null, rings: [] };
  }

  get doc() {
    return this.history.doc;
  }

  // ---- state -------------------------------------------------------------------------------

  setMode(mode) {
    if (!MODES.includes(mode)) return;
    this.mode = mode;
    this.draft = [];
    this.hoverPoint = null;
    if (mode !== "edit") this.selection = null;
    this.onState();
    this.view.draw();
  }

  /** The drawing modes wait for corners; Finish closes the polygon. */
  get drawing() {
    return DRAW_MODES.has(this.mode) || this.mode === "abline";
  }

  select(selection) {
    this.selection = selection;
    this.onState();
    this.view.draw();
  }

  /** The selected feature's index and role, or null. */
  get selectedFeature() {
    if (!this.selection) return null;
    const f = this.doc?.features?.[this.selection.feature];
    return f ? { index: this.selection.feature, role: roleOf(f), feature: f } : null;
  }

  /** The rings of the document in world metres (cached per document and projection). */
  rings() {
    const p = this.projection();
    if (this.cache.doc !== this.doc || this.cache.projection !== p) {
      this.cache = {
        doc: this.doc,
        projection: p,
        rings: p ? editableRings(this.doc).map((r) => ({ ...r, world: r.points.map(p.forward) })) : [],
      };
    }
    return this.cache.rings;
  }

  change(doc, final) {
    if (!doc) return;
    if (final) this.history.push(doc);
    else this.history.preview(doc);
    this.onChange(doc, { final });
    this.onState();
  }

  toLonLat(world) {
    return this.projection()?.inverse(world) ?? null;
  }

  screenOf(world) {
    return this.view.toScreen(world);
  }

  // ---- hit testing ---------------------------------------------------------------------------

  /** The handle under screen point `pt` ({x, y}) in edit mode, or null (then the map pans). */
  hit(pt) {
    if (this.mode !== "edit" || !this.doc) return null;
    let best = null;
    const consider = (target, world, extra = 0) => {
      const [sx, sy] = this.screenOf(world);
      const d = Math.hypot(sx - pt.x, sy - pt.y) + extra;
      if (d <= HIT_PX + extra && (!best || d < best.d)) best = { ...target, d };
    };
    const entrance = entranceOf(this.doc);
    const p = this.projection();
    if (entrance && p) consider({ type: "entrance" }, p.forward(entrance));
    const line = referenceLineOf(this.doc);
    if (line && p) line.forEach((q, end) => consider({ type: "ab", end }, p.forward(q)));
    for (const r of this.rings()) {
      const ref = { feature: r.feature, part: r.part, ring: r.ring };
      r.world.forEach((w, i) => consider({ type: "vertex", ref, i }, w));
      // Insert marks lose to vertices: a small penalty keeps a vertex first where both are near.
      this.midpoints(r).forEach(({ i, world }) => consider({ type: "mid", ref, i }, world, 4));
    }
    return best;
  }

  /** The middles of the ring's edges long enough on screen to carry an insert mark. */
  midpoints(r) {
    const out = [];
    const n = r.world.length;
    for (let i = 0; i < n; i++) {
      const a = r.world[i];
      const b = r.world[(i + 1) % n];
      const [ax, ay] = this.screenOf(a);
      const [bx, by] = this.screenOf(b);
      if (Math.hypot(bx - ax, by - ay) < MID_MIN_PX) continue;
      out.push({ i, world: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] });
    }
    return out;
  }

  // ---- pointer events from the view ---------------------------------------------------------

  /** A handle is dragged to screen point `pt`. */
  drag(target, pt) {
    const world = this.view.toWorld(pt.x, pt.y);
    const lonLat = this.toLonLat(world);
    if (!lonLat) return;
    if (!this.dragging || this.dragging.target !== target) {
      let base = this.doc;
      let moving = target;
      if (target.type === "mid") {
        // Dragging an insert mark puts a vertex there and drags it.
        base = insertVertex(base, target.ref, target.i, lonLat);
        if (!base) return;
        moving = { type: "vertex", ref: target.ref, i: target.i + 1 };
      }
      this.dragging = { target, base, moving };
      if (moving.type === "vertex") this.selection = { ...moving.ref, vertex: moving.i };
    }
    const { base, moving } = this.dragging;
    let doc = null;
    if (moving.type === "vertex") doc = moveVertex(base, moving.ref, moving.i, lonLat);
    else if (moving.type === "entrance") doc = setEntrance(base, lonLat);
    else if (moving.type === "ab") {
      const line = referenceLineOf(base);
      if (line) {
        line[moving.end] = lonLat;
        doc = setReferenceLine(base, line);
      }
    }
    this.change(doc, false);
  }

  /** The press on a handle ends; `moved`: it was dragged (else it was a tap on the handle). */
  release(target, pt, moved) {
    const dragging = this.dragging;
    this.dragging = null;
    if (moved && dragging) {
      this.change(this.doc, true);
      return;
    }
    if (target.type === "vertex") this.select({ ...target.ref, vertex: target.i });
    else if (target.type === "entrance" || target.type === "ab") {
      // Selected, so that Delete removes it.
      const role = target.type === "entrance" ? "entrance" : "reference_line";
      const feature = this.doc.features.findIndex((f) => roleOf(f) === role);
      if (feature >= 0) this.select({ feature, part: 0, ring: 0, vertex: null });
    }
    else if (target.type === "mid") {
      // A tap on an insert mark puts a vertex in the middle of the edge.
      const r = this.rings().find((x) => sameRing(x, target.ref));
      const a = r?.world[target.i];
      const b = r?.world[(target.i + 1) % (r?.world.length ?? 1)];
      const at = a && b ? [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] : this.view.toWorld(pt.x, pt.y);
      const doc = insertVertex(this.doc, target.ref, target.i, this.toLonLat(at));
      if (doc) {
        this.selection = { ...target.ref, vertex: target.i + 1 };
        this.change(doc, true);
      }
    }
  }

  /** A press that did not move, away from any handle. */
  tap(pt) {
    if (this.mode === "parcel") {
      this.onParcelTap(pt);
      return true;
    }
    if (!this.doc) return false;
    const world = this.view.toWorld(pt.x, pt.y);
    switch (this.mode) {
      case "edit":
        this.select(this.featureAt(world));
        return true;
      case "boundary":
      case "obstacle":
      case "prohibited": {
        if (this.draft.length >= 3) {
          const [fx, fy] = this.screenOf(this.draft[0]);
          if (Math.hypot(fx - pt.x, fy - pt.y) <= HIT_PX) {
            this.finish();
            return true;
          }
        }
        const last = this.draft[this.draft.length - 1];
        if (last) {
          const [lx, ly] = this.screenOf(last);
          if (Math.hypot(lx - pt.x, ly - pt.y) < 3) return true; // the second tap of a double tap
        }
        this.draft.push(world);
        this.onState();
        this.view.draw();
        return true;
      }
      case "entrance": {
        const lonLat = this.toLonLat(world);
        if (lonLat) this.change(setEntrance(this.doc, lonLat), true);
        this.setMode("edit");
        return true;
      }
      case "abline": {
        this.draft.push(world);
        if (this.draft.length === 2) {
          const line = this.draft.map((w) => this.toLonLat(w));
          this.draft = [];
          if (line.every(Boolean)) {
            this.change(setReferenceLine(this.doc, line), true);
            this.onPickLine(line);
          }
          this.setMode("edit");
        } else {
          this.onState();
          this.view.draw();
        }
        return true;
      }
      case "way":
        this.onWayTap(world);
        return true;
      case "edge": {
        const edge = this.boundaryEdgeAt(pt);
        if (edge != null) {
          this.onPickEdge(edge);
          this.setMode("edit");
        }
        return true;
      }
      default:
        return false;
    }
  }

  /** A double tap or double click: closes the polygon being drawn (instead of zooming). */
  doubleTap() {
    if (!DRAW_MODES.has(this.mode)) return false;
    if (this.draft.length >= 3) this.finish();
    return true;
  }

  /** The mouse moves with no button down: the draft's rubber band follows it. */
  hover(pt) {
    if (!this.drawing || !this.draft.length) return;
    this.hoverPoint = this.view.toWorld(pt.x, pt.y);
    this.view.requestDraw();
  }

  /** Keys on the map: Delete, Escape, Enter, Backspace while drawing; undo and redo. */
  key(e) {
    const mod = e.ctrlKey || e.metaKey;
    if (mod && e.key.toLowerCase() === "z") {
      if (e.shiftKey) this.redo();
      else this.undo();
      return true;
    }
    if (mod && e.key.toLowerCase() === "y") {
      this.redo();
      return true;
    }
    if (mod || e.altKey) return false;
    if (this.drawing) {
      if (e.key === "Enter") this.finish();
      else if (e.key === "Escape") this.setMode("edit");
      else if (e.key === "Backspace") {
        this.draft.pop();
        this.onState();
        this.view.draw();
      } else return false;
      return true;
    }
    if (e.key === "Delete" || e.key === "Backspace") {
      this.deleteSelection();
      return true;
    }
    if (e.key === "Escape" && this.selection) {
      this.select(null);
      return true;
    }
    return false;
  }

  // ---- actions -------------------------------------------------------------------------------

  /** Closes the polygon being drawn; it becomes the boundary, an obstacle or a prohibited region. */
  finish() {
    if (!DRAW_MODES.has(this.mode)) return false;
    // A double tap leaves two corners at one place: keep one.
    const pts = [];
    for (const w of this.draft) {
      const last = pts[pts.length - 1];
      if (!last || Math.hypot(w[0] - last[0], w[1] - last[1]) * this.view.scale >= 3) pts.push(w);
    }
    if (pts.length < 3) return false;
    const lonLats = pts.map((w) => this.toLonLat(w));
    if (!lonLats.every(Boolean)) return false;
    const role = this.mode;
    const props = role === "prohibited" ? { forbidden_bearings_deg: DEFAULT_FORBIDDEN } : {};
    const added = addPolygon(this.doc, role, lonLats, props);
    this.draft = [];
    if (!added) return false;
    this.change(added.doc, true);
    this.mode = "edit";
    this.select({ feature: added.feature, part: 0, ring: 0, vertex: null });
    return true;
  }

  /** Removes the selected vertex (a ring keeps three), or the selected obstacle, region or extra. */
  deleteSelection() {
    const s = this.selection;
    if (!s) return false;
    let doc = null;
    if (s.vertex != null) doc = deleteVertex(this.doc, s, s.vertex);
    if (!doc && (s.vertex == null || s.ring === 0)) {
      const role = roleOf(this.doc.features[s.feature]);
      // The field itself is not deleted by a tap; a new field starts from "New".
      if (role !== "boundary" && role !== "field" && role !== null) doc = deleteFeature(this.doc, s.feature);
    }
    if (!doc) return false;
    this.selection = null;
    this.change(doc, true);
    return true;
  }

  undo() {
    return this.showStep(this.history.undo());
  }

  redo() {
    return this.showStep(this.history.redo());
  }

  /** Shows a step of the history that undo or redo went to (null: there was none). */
  showStep(doc) {
    if (!doc) return false;
    this.selection = null;
    this.onChange(doc, { final: true });
    this.onState();
    return true;
  }

  /** The outlines of `rings` (of rings()) as the context's path, in screen px. */
  ringsPath(ctx, rings) {
    ctx.beginPath();
    for (const r of rings) {
      r.world.forEach((w, i) => {
        const [x, y] = this.screenOf(w);
        if (i === 0) ctx.moveTo(x, y);
        else ctx.lineTo(x, y);
      });
      ctx.closePath();
    }
  }

  /** The smallest polygon under world point `w`: an obstacle or region before the field. */
  featureAt(w) {
    let best = null;
    for (const r of this.rings()) {
      if (r.ring !== 0 || !insidePolygon(w, [r.world])) continue;
      const area = Math.abs(ringArea(r.world));
      if (!best || area < best.area) best = { area, sel: { feature: r.feature, part: r.part, ring: 0, vertex: null } };
    }
    return best?.sel ?? null;
  }

  /** The index of the boundary's edge nearest screen point `pt` (within a touch target), or null. */
  boundaryEdgeAt(pt) {
    const boundary = this.rings().find((r) => (r.role === "boundary" || r.role === "field") && r.ring === 0 && r.part === 0)
      ?? this.rings().find((r) => r.ring === 0);
    if (!boundary) return null;
    let best = null;
    const n = boundary.world.length;
    for (let i = 0; i < n; i++) {
      const a = this.screenOf(boundary.world[i]);
      const b = this.screenOf(boundary.world[(i + 1) % n]);
      const d = segmentDistance([pt.x, pt.y], a, b);
      if (d <= HIT_PX && (!best || d < best.d)) best = { i, d };
    }
    return best?.i ?? null;
  }

  /** Screen points ([x, y] CSS px) of the marks the user presses or is putting down: corners
   * and insert marks while editing, the corners tapped while drawing, the entrance, A and B. */
  handlePoints() {
    const p = this.projection();
    if (!p || !this.doc) return [];
    const out = [];
    const line = referenceLineOf(this.doc);
    if (line) out.push(...line.map((q) => this.screenOf(p.forward(q))));
    const entrance = entranceOf(this.doc);
    if (entrance) out.push(this.screenOf(p.forward(entrance)));
    if (this.mode === "edit") {
      for (const r of this.rings()) {
        for (const w of r.world) out.push(this.screenOf(w));
        for (const m of this.midpoints(r)) out.push(this.screenOf(m.world));
      }
    }
    if (this.drawing) for (const w of this.draft) out.push(this.screenOf(w));
    return out;
  }

  // ---- drawing -------------------------------------------------------------------------------

  /** The tool's marks over the map: handles in edit mode, the draft, the entrance and AB line. */
  draw(ctx, t) {
    const p = this.projection();
    if (!p || !this.doc) return;
    const line = referenceLineOf(this.doc);
    if (line) this.drawLine(ctx, t, line.map(p.forward));
    const entrance = entranceOf(this.doc);
    if (entrance) this.drawEntrance(ctx, t, p.forward(entrance), this.selectedFeature?.role === "entrance");
    if (this.mode === "edit") this.drawHandles(ctx, t);
    if (this.drawing && this.draft.length) this.drawDraft(ctx, t);
  }

  drawHandles(ctx, t) {
    const s = this.selection;
    const rings = this.rings();
    // The selected feature's outline, thick.
    if (s) {
      this.ringsPath(
        ctx,
        rings.filter((r) => r.feature === s.feature),
      );
      ctx.lineWidth = 5;
      ctx.strokeStyle = t.select;
      ctx.stroke();
    }
    ctx.beginPath();
    for (const r of rings) {
      for (const { world } of this.midpoints(r)) {
        const [x, y] = this.screenOf(world);
        ctx.moveTo(x + 4, y);
        ctx.arc(x, y, 4, 0, 2 * Math.PI);
      }
    }
    ctx.lineWidth = 1.5;
    ctx.fillStyle = t.labelFill;
    ctx.globalAlpha = 0.85;
    ctx.fill();
    ctx.globalAlpha = 1;
    ctx.strokeStyle = t.label;
    ctx.stroke();
    ctx.beginPath();
    for (const r of rings) {
      for (const w of r.world) {
        const [x, y] = this.screenOf(w);
        ctx.moveTo(x + 5.5, y);
        ctx.arc(x, y, 5.5, 0, 2 * Math.PI);
      }
    }
    ctx.fillStyle = t.labelFill;
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = t.label;
    ctx.stroke();
    if (s?.vertex != null) {
      const r = rings.find((x) => sameRing(x, s));
      const w = r?.world[s.vertex];
      if (w) {
        const [x, y] = this.screenOf(w);
        ctx.beginPath();
        ctx.arc(x, y, 9, 0, 2 * Math.PI);
        ctx.fillStyle = t.select;
        ctx.fill();
        ctx.lineWidth = 2.5;
        ctx.strokeStyle = t.labelFill;
        ctx.stroke();
      }
    }
  }

  drawDraft(ctx, t) {
    const pts = this.draft.map((w) => this.screenOf(w));
    const closed = this.mode !== "abline";
    ctx.beginPath();
    pts.forEach(([x, y], i) => (i === 0 ? ctx.moveTo(x, y) : ctx.lineTo(x, y)));
    if (this.hoverPoint) {
      const [hx, hy] = this.screenOf(this.hoverPoint);
      ctx.lineTo(hx, hy);
      if (closed && pts.length >= 2) ctx.lineTo(pts[0][0], pts[0][1]);
    }
    ctx.setLineDash([6, 4]);
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = t.select;
    ctx.stroke();
    ctx.setLineDash([]);
    pts.forEach(([x, y], i) => {
      ctx.beginPath();
      ctx.arc(x, y, i === 0 && closed && pts.length >= 3 ? 9 : 5.5, 0, 2 * Math.PI);
      ctx.fillStyle = i === 0 ? t.select : t.labelFill;
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.label;
      ctx.stroke();
    });
  }

  /** The entrance: a disc with an arrow into the field. */
  drawEntrance(ctx, t, w, selected) {
    const [x, y] = this.screenOf(w);
    if (selected) {
      ctx.beginPath();
      ctx.arc(x, y, 16, 0, 2 * Math.PI);
      ctx.lineWidth = 4;
      ctx.strokeStyle = t.select;
      ctx.stroke();
    }
    ctx.beginPath();
    ctx.arc(x, y, 11, 0, 2 * Math.PI);
    ctx.fillStyle = t.entrance;
    ctx.fill();
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = t.labelFill;
    ctx.stroke();
    ctx.fillStyle = t.labelFill;
    ctx.font = `800 12px system-ui, sans-serif`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    ctx.fillText("E", x, y + 0.5);
  }

  /** The AB line, carried on across the view, with A and B marked. */
  drawLine(ctx, t, [a, b]) {
    const [ax, ay] = this.screenOf(a);
    const [bx, by] = this.screenOf(b);
    const len = Math.hypot(bx - ax, by - ay);
    if (len > 1e-6) {
      const far = (this.view.cssW + this.view.cssH) * 2;
      const ux = (bx - ax) / len;
      const uy = (by - ay) / len;
      ctx.beginPath();
      ctx.moveTo(ax - ux * far, ay - uy * far);
      ctx.lineTo(bx + ux * far, by + uy * far);
      ctx.setLineDash([3, 6]);
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.reference;
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.beginPath();
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
      ctx.lineWidth = 3;
      ctx.stroke();
    }
    ctx.font = `800 12px system-ui, sans-serif`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    for (const [x, y, text] of [
      [ax, ay, "A"],
      [bx, by, "B"],
    ]) {
      ctx.beginPath();
      ctx.arc(x, y, 10, 0, 2 * Math.PI);
      ctx.fillStyle = t.reference;
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
      ctx.fillStyle = t.labelFill;
      ctx.fillText(text, x, y + 0.5);
    }
  }
}

function sameRing(r, ref) {
  return r.feature === ref.feature && r.part === ref.part && r.ring === ref.ring;
}

function ringArea(pts) {
  let a = 0;
  for (let i = 0, j = pts.length - 1; i < pts.length; j = i++) a += pts[j][0] * pts[i][1] - pts[i][0] * pts[j][1];
  return a / 2;
}

/** Distance from point p to segment ab (screen px). */
function segmentDistance([px, py], [ax, ay], [bx, by]) {
  const dx = bx - ax;
  const dy = by - ay;
  const l2 = dx * dx + dy * dy;
  const u = l2 > 0 ? Math.max(0, Math.min(1, ((px - ax) * dx + (py - ay) * dy) / l2)) : 0;
  return Math.hypot(px - (ax + u * dx), py - (ay + u * dy));
}
