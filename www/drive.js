// Drives the machine along the planned path on the map: a marker as wide as the implement, facing
// its heading, moving along the plan's samples (plan.samples, typed arrays) at the plan's own
// working and turning speeds times a chosen factor. The trail behind it is drawn in the machine's
// colour, so that a driver sees what is done and what is left.
//
//   const driver = new Driver(view, { onState });
//   driver.setPlan(plan.samples, projection, width);
//   driver.start(100);   // 100 × the machine's speed
//   driver.stop();
//   view.overlay = (ctx, theme) => driver.draw(ctx, theme);

/** Where the machine is at time `t` (seconds) along samples `s`: `{ i, u }`, the sample before it
 * and the fraction of the way to the next. Binary search over `s.time_s`. */
export function positionAt(s, t) {
  const time = s.time_s;
  const n = time.length;
  if (n === 0) return null;
  if (t <= time[0]) return { i: 0, u: 0 };
  if (t >= time[n - 1]) return { i: n - 1, u: 0 };
  let lo = 0;
  let hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (time[mid] <= t) lo = mid;
    else hi = mid;
  }
  const span = time[hi] - time[lo];
  return { i: lo, u: span > 0 ? (t - time[lo]) / span : 0 };
}

export class Driver {
  constructor(view, { onState } = {}) {
    this.view = view;
    this.onState = onState ?? (() => {});
    this.samples = null;
    this.projection = null;
    this.world = null; // Float64Array of x, y pairs in the view's metres
    this.width = 6;
    this.t = 0; // seconds of plan time driven
    this.factor = 100;
    this.running = false;
    this.frame = 0;
    this.last = 0;
  }

  /** The plan to drive (its samples in lon/lat), or null. Stops a drive in progress. The samples
   * are projected when first driven, not on every plan (a drag re-plans many times a second). */
  setPlan(samples, projection, width) {
    this.stop();
    this.t = 0;
    this.samples = samples?.time_s?.length ? samples : null;
    this.projection = projection ?? null;
    this.world = null;
    if (Number.isFinite(width) && width > 0) this.width = width;
  }

  /** The samples in the view's metres, as x, y pairs. */
  project() {
    if (this.world || !this.samples || !this.projection) return this.world;
    const n = this.samples.x.length;
    const world = new Float64Array(2 * n);
    for (let i = 0; i < n; i++) {
      const [x, y] = this.projection.forward([this.samples.x[i], this.samples.y[i]]);
      world[2 * i] = x;
      world[2 * i + 1] = y;
    }
    this.world = world;
    return world;
  }

  /** Total plan time, seconds. */
  get duration() {
    const time = this.samples?.time_s;
    return time?.length ? time[time.length - 1] : 0;
  }

  start(factor = this.factor) {
    if (!this.project()) return false;
    this.factor = factor;
    if (this.t >= this.duration) this.t = 0;
    this.running = true;
    this.last = performance.now();
    this.tick();
    this.onState();
    return true;
  }

  stop() {
    if (this.frame) cancelAnimationFrame(this.frame);
    this.frame = 0;
    const was = this.running;
    this.running = false;
    if (was) this.onState();
  }

  tick() {
    this.frame = requestAnimationFrame((now) => {
      this.frame = 0;
      if (!this.running) return;
      // A frame long delayed (a background tab) does not jump the machine far ahead.
      const dt = Math.min(0.25, Math.max(0, (now - this.last) / 1000));
      this.last = now;
      this.t = Math.min(this.duration, this.t + dt * this.factor);
      this.view.draw();
      if (this.t >= this.duration) {
        this.running = false;
        this.onState();
        return;
      }
      this.onState();
      this.tick();
    });
  }

  /** The machine's pose now: `{ x, y, headingDeg, reverse, working, i }` in the view's metres. */
  pose() {
    if (!this.samples || !this.world) return null;
    const at = positionAt(this.samples, this.t);
    if (!at) return null;
    const { i, u } = at;
    const j = Math.min(i + 1, this.samples.x.length - 1);
    const w = this.world;
    const x = w[2 * i] + (w[2 * j] - w[2 * i]) * u;
    const y = w[2 * i + 1] + (w[2 * j + 1] - w[2 * i + 1]) * u;
    const h0 = this.samples.heading_deg[i];
    let dh = this.samples.heading_deg[j] - h0;
    if (dh > 180) dh -= 360;
    if (dh < -180) dh += 360;
    return {
      x,
      y,
      headingDeg: h0 + dh * u,
      reverse: this.samples.reverse[i] === 1,
      working: this.samples.working[i] === 1,
      i,
    };
  }

  /** The trail driven so far and the machine, over the map. */
  draw(ctx, theme) {
    if (!this.world || (this.t <= 0 && !this.running)) return;
    const pose = this.pose();
    if (!pose) return;
    const view = this.view;
    const w = this.world;
    // The trail: every sample up to the machine (thinned to about one per screen pixel).
    ctx.beginPath();
    let [px, py] = view.toScreen([w[0], w[1]]);
    ctx.moveTo(px, py);
    for (let k = 1; k <= pose.i; k++) {
      const [sx, sy] = view.toScreen([w[2 * k], w[2 * k + 1]]);
      if (Math.abs(sx - px) + Math.abs(sy - py) < 1 && k < pose.i) continue;
      ctx.lineTo(sx, sy);
      px = sx;
      py = sy;
    }
    const [mx, my] = view.toScreen([pose.x, pose.y]);
    ctx.lineTo(mx, my);
    ctx.globalAlpha = 0.45;
    ctx.lineWidth = Math.max(3, this.width * view.scale);
    ctx.strokeStyle = theme.machine;
    ctx.lineCap = "butt";
    ctx.stroke();
    ctx.globalAlpha = 1;
    ctx.lineCap = "round";
    // The machine: the implement's bar across the heading and an arrow the way it faces.
    const a = (pose.headingDeg * Math.PI) / 180;
    const fx = Math.sin(a); // screen: x east, y down
    const fy = -Math.cos(a);
    const half = Math.max(8, (this.width * view.scale) / 2);
    const len = Math.max(16, half * 0.9);
    ctx.beginPath();
    ctx.moveTo(mx - fy * half, my + fx * half);
    ctx.lineTo(mx + fy * half, my - fx * half);
    ctx.lineWidth = 5;
    ctx.strokeStyle = theme.labelFill;
    ctx.stroke();
    ctx.lineWidth = 3;
    ctx.strokeStyle = theme.machine;
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(mx + fx * len, my + fy * len);
    ctx.lineTo(mx - fy * 7 - fx * 4, my + fx * 7 - fy * 4);
    ctx.lineTo(mx + fy * 7 - fx * 4, my - fx * 7 - fy * 4);
    ctx.closePath();
    ctx.fillStyle = pose.reverse ? theme.labelFill : theme.machine;
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = pose.reverse ? theme.machine : theme.labelFill;
    ctx.stroke();
  }
}
