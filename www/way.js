// The way out along the tracks (Plessen & Bemporad): the machine's place and heading and the exit,
// tapped on the map, and the shortest way along the plan's tracks between them, asked of the
// planner (planner.js, in its worker) and drawn over the map.
//
//   const way = new WayOut({ view, projection, entrance, turning, onState });
//   way.tap(worldPoint)    in the edit tool's "way" mode: place, then heading, then (once) exit
//   way.find()             asks again (after a new plan, or another turning)
//   way.draw(ctx, theme)   from the view's overlay
//   way.hint()             what to tap next, or the way found
import { sentence } from "./notes.js";
import { runPath } from "./planner.js";

export class WayOut {
  /**
   * @param {object} o
   * @param {import("./view.js").PlanView} o.view
   * @param {() => ({ forward: Function, inverse: Function } | null)} o.projection the field's
   * @param {() => number[] | null} o.entrance the field's entrance (lon/lat): the exit by default
   * @param {() => string} o.turning "tracks", "heading" or "on-the-spot"
   * @param {() => boolean} o.ready whether there is a plan to find a way along
   * @param {() => void} [o.onState] the step, the way or its error changed
   */
  constructor({ view, projection, entrance, turning, ready, onState }) {
    Object.assign(this, { view, projection, entrance, turning, ready });
    this.onState = onState ?? (() => {});
    this.seq = 0;
    this.reset();
  }

  /** Forgets the place, heading, exit and way (a new field). */
  reset() {
    this.step = "position"; // what the next tap gives: position, heading or exit
    this.position = null; // lon/lat
    this.heading = null; // compass degrees
    this.exit = null; // lon/lat
    this.path = null; // the way found: a GeoJSON Feature
    this.error = null;
    this.ms = null;
  }

  /** Whether a question is complete (place, heading and exit). */
  get asked() {
    return Boolean(this.position && this.heading != null && this.exit);
  }

  /** What to tap next, or the way found. */
  hint(format = (v) => String(Math.round(v))) {
    if (this.step === "heading") return "Tap where the machine faces.";
    if (this.step === "exit") return "Tap the exit on the field's edge.";
    const found = this.path
      ? `Way out: ${format(this.path.properties.length_m)} m. `
      : this.error
        ? `${sentence(this.error.message)} `
        : "";
    const then = this.exit ? "then where it faces" : "then where it faces, then the exit on the field's edge";
    return `${found}Tap where the machine is, ${then}.`;
  }

  /** A tap (world metres): the machine's place, then where it faces, then (once) the exit; the
   * field's entrance is the exit when there is one. */
  tap(world) {
    const p = this.projection();
    if (!p) return;
    const lonLat = p.inverse(world);
    if (this.step === "position") {
      Object.assign(this, { position: lonLat, heading: null, path: null, error: null, step: "heading" });
    } else if (this.step === "heading") {
      const from = p.forward(this.position);
      const dx = world[0] - from[0];
      const dy = world[1] - from[1];
      if (Math.hypot(dx, dy) * this.view.scale < 6) return; // the same place: tap a little way off
      this.heading = ((Math.atan2(dx, dy) * 180) / Math.PI + 360) % 360;
      this.exit ??= this.entrance();
      this.step = this.exit ? "position" : "exit";
      if (this.exit) this.find();
    } else {
      this.exit = lonLat;
      this.step = "position";
      this.find();
    }
    this.onState();
    this.view.draw();
  }

  /** Asks the planner for the way; the newest question wins. */
  async find() {
    if (!this.asked || !this.ready()) return;
    const seq = ++this.seq;
    this.finding = true;
    this.onState();
    const result = await runPath(this.position, this.heading, this.exit, { turning: this.turning() });
    if (seq !== this.seq) return;
    this.finding = false;
    this.path = result.path ?? null;
    this.error = result.error ?? null;
    this.ms = result.ms;
    this.onState();
    this.view.draw();
  }

  /** The state for `body[data-way]`: position, heading, exit, planning, ready or error. */
  get state() {
    if (this.finding) return "planning";
    if (this.path) return "ready";
    return this.error ? "error" : this.step;
  }

  /** The way, the machine facing its heading, and the exit, over the map. `shown`: the tool is in
   * the way-out mode (else only a way found is drawn). */
  draw(ctx, t, shown) {
    const p = this.projection();
    if (!p || (!shown && !this.path)) return;
    const screen = (lonLat) => this.view.toScreen(p.forward(lonLat));
    if (this.path) {
      const pts = this.path.geometry.coordinates.map(screen);
      ctx.beginPath();
      pts.forEach(([x, y], i) => (i === 0 ? ctx.moveTo(x, y) : ctx.lineTo(x, y)));
      ctx.setLineDash([]);
      ctx.lineWidth = 8;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
      ctx.lineWidth = 4.5;
      ctx.strokeStyle = t.way;
      ctx.stroke();
    }
    if (this.exit) {
      const [x, y] = screen(this.exit);
      ctx.beginPath();
      ctx.rect(x - 8, y - 8, 16, 16);
      ctx.fillStyle = t.way;
      ctx.fill();
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
    }
    if (!this.position) return;
    const [x, y] = screen(this.position);
    ctx.beginPath();
    ctx.arc(x, y, 8, 0, 2 * Math.PI);
    ctx.fillStyle = t.way;
    ctx.fill();
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = t.labelFill;
    ctx.stroke();
    if (this.heading == null) return;
    const a = (this.heading * Math.PI) / 180;
    const [fx, fy] = [Math.sin(a), -Math.cos(a)];
    ctx.beginPath();
    ctx.moveTo(x + fx * 26, y + fy * 26);
    ctx.lineTo(x + fx * 10 - fy * 7, y + fy * 10 + fx * 7);
    ctx.lineTo(x + fx * 10 + fy * 7, y + fy * 10 - fx * 7);
    ctx.closePath();
    ctx.fillStyle = t.way;
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = t.labelFill;
    ctx.stroke();
  }
}
