// What the planner says about a field, in words on the map next to the place it concerns.
//
// - The error callout (#map-message): when there is no plan. Anchored beside a point (the error's
//   coordinate, or a point on the outline of the feature it names) with a tail pointing at it, or,
//   when the error has no place, a banner across the top of the map. It can be folded to its title
//   line so that it does not hide the field.
// - Warning notes: a small badge on the outline of each feature that warnings name (several
//   warnings on one feature share one badge, with their number); hovering, focusing or tapping the
//   badge opens a card with the messages (tap again or Escape to close), and the feature's outline
//   is highlighted while it is open.
//
// Both are DOM elements over the canvas, so the words are real text (selectable, read by screen
// readers, zoomable). Places are in the view's metres; layout() moves everything to the view and
// runs after every frame the view draws.

/** What to do about each error (from the README's error reference). */
export const ERROR_HINTS = {
  invalid_json: "Export the field again and check that the file is complete.",
  invalid_geojson: "Fix the part of the file the message names.",
  ambiguous_boundary: "Mark one polygon as the boundary and the others as obstacles.",
  unsupported_geometry: "Draw it as a polygon.",
  non_finite_coordinate: "Re-record or delete that corner.",
  coordinate_out_of_range:
    "Check that positions are written longitude first, then latitude, and that the file is in degrees (WGS84).",
  too_few_points: "Draw at least three corners.",
  zero_area: "Draw the outline of the field, not a line.",
  self_intersection: "Move the corners so that the outline does not cross itself.",
  obstacle_outside_field: "Move the obstacle into the field, or remove it.",
  hole_crossing_boundary: "Make the hole an obstacle inside the field.",
  input_too_large: "Simplify the boundary: a few corners per metre of work are plenty.",
  field_too_large: "Check the coordinate system and that the working width is in metres.",
  no_allowed_direction: "Leave some driving directions open.",
  bearing_forbidden: "Choose another bearing, or leave it empty to let the planner choose.",
  coordinates_swapped: "Write positions as [longitude, latitude]: export the field again.",
  internal: "Please report this with the field and the settings.",
};

const MARGIN = 8; // CSS px kept free along the map's edges
const MAX_CARD_WIDTH = 360;
const ERROR_GAP = 28; // from the anchor to the error callout: clears the ring-and-cross marker
const WARNING_GAP = 16; // from the badge centre to its card
const BADGE_SPACING = 30; // badges closer than this are moved apart
const HOVER_CLOSE_MS = 250;

/** "the field falls…" -> "The field falls….": the planner's messages start lower case. */
export function sentence(text) {
  const t = String(text ?? "").trim();
  if (!t) return t;
  const s = t[0].toUpperCase() + t.slice(1);
  return /[.!?]$/.test(s) ? s : `${s}.`;
}

/** A feature as a farmer calls it: "Field boundary", "Obstacle 2", "Feature 3". */
export function featureLabel(feature, index) {
  const role = feature?.role;
  if (role === "boundary") return "Field boundary";
  if (feature?.name) return sentence(feature.name).replace(/\.$/, "");
  const kind = { obstacle: "Obstacle", prohibited: "Prohibited region" }[role] ?? "Feature";
  return `${kind} (feature ${index})`;
}

const el = (tag, props = {}, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(props)) {
    if (k === "class") e.className = v;
    else if (k === "text") e.textContent = v;
    else if (k.startsWith("data-") || k.startsWith("aria-") || k === "role") e.setAttribute(k, v);
    else e[k] = v;
  }
  e.append(...children);
  return e;
};

export class MapNotes {
  /**
   * @param {{ map: HTMLElement, layer: HTMLElement, error: HTMLElement, tools: HTMLElement, view: object }} parts
   *   map: the positioned map section; layer: the overlay for warning notes; error: #map-message;
   *   tools: the zoom buttons (kept clear); view: the PlanView (toScreen, cssW, cssH).
   */
  constructor({ map, layer, error, tools, view }) {
    this.map = map;
    this.layer = layer;
    this.errorEl = error;
    this.tools = tools;
    this.view = view;
    this.error = null; // { anchor, expanded }
    this.groups = []; // { feature, anchor, warnings, root, badge, card, pinned, hover, focus }
    this.onOpenChange = null; // (open groups) => void
    this.buildErrorCallout();
    document.addEventListener("keydown", (e) => {
      if (e.key === "Escape" && this.groups.some((g) => this.isOpen(g))) {
        for (const g of this.groups) g.pinned = g.hover = g.focus = false;
        this.refreshOpen();
      }
    });
  }

  // ---- the error callout ---------------------------------------------------------------------

  buildErrorCallout() {
    const e = this.errorEl;
    this.errorParts = {
      title: el("strong", { class: "callout-title" }),
      toggle: el("button", { type: "button", class: "callout-toggle", "aria-expanded": "true", text: "Hide" }),
      body: el("div", { class: "callout-body", id: "map-message-body" }),
      tail: el("span", { class: "callout-tail", "aria-hidden": "true" }),
    };
    const { title, toggle, body, tail } = this.errorParts;
    toggle.setAttribute("aria-controls", body.id);
    toggle.addEventListener("click", () => {
      if (!this.error) return;
      this.error.expanded = !this.error.expanded;
      this.renderErrorExpanded();
      this.layout();
    });
    e.classList.add("callout", "callout-error");
    e.replaceChildren(el("div", { class: "callout-head" }, title, toggle), body, tail);
  }

  /**
   * Shows an error: `{ code, feature?, title, text, hint?, detail?, excerpt?, anchor }`, anchor
   * in metres or null for a banner.
   */
  showError({ code, feature, title, text, hint, detail, excerpt, anchor }) {
    const e = this.errorEl;
    const { title: t, body } = this.errorParts;
    t.textContent = title;
    const paragraphs = [el("p", { class: "callout-text", text })];
    if (excerpt) {
      paragraphs.push(
        el(
          "p",
          { class: "callout-excerpt" },
          "Near ",
          el("code", {}, excerpt.before, el("mark", { text: excerpt.at || " " }), excerpt.after),
        ),
      );
    }
    if (hint) paragraphs.push(el("p", { class: "callout-hint", text: hint }));
    if (detail) paragraphs.push(el("p", { class: "callout-detail", text: detail }));
    body.replaceChildren(...paragraphs);
    e.dataset.code = code;
    if (Number.isInteger(feature)) e.dataset.feature = String(feature);
    else delete e.dataset.feature;
    e.classList.toggle("anchored", !!anchor);
    e.classList.toggle("banner", !anchor);
    this.error = { anchor, expanded: true };
    this.renderErrorExpanded();
    e.hidden = false;
    this.layout();
  }

  hideError() {
    const e = this.errorEl;
    this.error = null;
    e.hidden = true;
    e.classList.remove("anchored", "banner");
    delete e.dataset.code;
    delete e.dataset.feature;
    this.errorParts.title.textContent = "";
    this.errorParts.body.replaceChildren();
  }

  renderErrorExpanded() {
    const { toggle, body } = this.errorParts;
    const expanded = this.error?.expanded ?? true;
    body.hidden = !expanded;
    toggle.textContent = expanded ? "Hide" : "Show";
    toggle.setAttribute("aria-expanded", String(expanded));
    toggle.setAttribute("aria-label", expanded ? "Hide the message" : "Show the message");
    // A banner does not cover the place it is about: no need to fold it.
    toggle.hidden = !this.error?.anchor;
  }

  // ---- warning notes -------------------------------------------------------------------------

  /** Shows warning groups: `[{ feature, label, anchor, warnings: [{ code, message }] }]`. */
  showWarnings(groups) {
    this.clearWarnings({ notify: false });
    this.groups = groups.map((g, i) => this.buildGroup(g, i));
    this.layer.replaceChildren(...this.groups.map((g) => g.root));
    this.layout();
  }

  clearWarnings({ notify = true } = {}) {
    const wasOpen = this.groups.some((g) => this.isOpen(g));
    this.groups = [];
    this.layer.replaceChildren();
    if (notify && wasOpen) this.onOpenChange?.([]);
  }

  buildGroup({ feature, label, anchor, warnings }, i) {
    const n = warnings.length;
    const id = `warning-note-${i}`;
    const texts = warnings.map((w) => sentence(w.message || w.code));
    const card = el(
      "div",
      { class: "callout callout-warning", id, role: "note", hidden: true, "aria-label": `${label}: warnings` },
      el("strong", { class: "callout-title", text: n > 1 ? `${label}: ${n} warnings` : label }),
      el(
        "ul",
        { class: "callout-list" },
        ...warnings.map((w, k) => el("li", { "data-code": w.code, text: texts[k] })),
      ),
      el("span", { class: "callout-tail", "aria-hidden": "true" }),
    );
    const badge = el(
      "button",
      {
        type: "button",
        class: "note-badge",
        "aria-expanded": "false",
        "aria-controls": id,
        "aria-label": `${n > 1 ? `${n} warnings` : "Warning"} about the ${label.toLowerCase()}: ${texts.join(" ")}`,
      },
      el("span", { class: "pip", "aria-hidden": "true" }, "!", n > 1 ? el("b", { text: String(n) }) : ""),
    );
    const root = el(
      "div",
      { class: "map-note", "data-feature": String(feature), "data-code": warnings.map((w) => w.code).join(" ") },
      badge,
      card,
    );
    const g = { feature, anchor, warnings, root, badge, card, pinned: false, hover: false, focus: false };
    badge.addEventListener("click", () => {
      const pin = !g.pinned;
      for (const other of this.groups) other.pinned = false;
      g.pinned = pin;
      if (!pin) g.hover = g.focus = false; // a tap or click closes it even while hovered or focused
      this.refreshOpen();
    });
    // Hover opens the card; it closes a moment after the pointer leaves both badge and card, so
    // that the pointer can cross from one to the other.
    let leaving = 0;
    for (const target of [badge, card]) {
      target.addEventListener("pointerenter", (e) => {
        if (e.pointerType !== "mouse") return;
        clearTimeout(leaving);
        if (!g.hover) {
          g.hover = true;
          this.refreshOpen();
        }
      });
      target.addEventListener("pointerleave", (e) => {
        if (e.pointerType !== "mouse") return;
        clearTimeout(leaving);
        leaving = setTimeout(() => {
          g.hover = false;
          this.refreshOpen();
        }, HOVER_CLOSE_MS);
      });
    }
    badge.addEventListener("focus", () => {
      if (!badge.matches(":focus-visible")) return; // a keyboard, not a tap
      g.focus = true;
      this.refreshOpen();
    });
    badge.addEventListener("blur", () => {
      g.focus = false;
      this.refreshOpen();
    });
    return g;
  }

  isOpen(g) {
    return g.pinned || g.hover || g.focus;
  }

  refreshOpen() {
    const open = [];
    for (const g of this.groups) {
      const isOpen = this.isOpen(g);
      g.badge.setAttribute("aria-expanded", String(isOpen));
      g.root.classList.toggle("open", isOpen);
      g.card.hidden = !isOpen;
      if (isOpen) open.push(g);
    }
    this.layout();
    this.onOpenChange?.(open);
  }

  // ---- layout --------------------------------------------------------------------------------

  /** Moves the callout and the notes to where their places are on the map now. */
  layout() {
    const W = this.map.clientWidth;
    const H = this.map.clientHeight;
    if (!W || !H) return;
    const mapRect = this.map.getBoundingClientRect();
    const t = this.tools.getBoundingClientRect();
    const tools = {
      left: t.left - mapRect.left - 6,
      top: t.top - mapRect.top - 6,
      right: t.right - mapRect.left + 6,
      bottom: t.bottom - mapRect.top + 6,
    };
    const box = { W, H, tools };
    const toScreen = (p) => this.view.toScreen(p);

    if (this.error && !this.errorEl.hidden) {
      const e = this.errorEl;
      if (this.error.anchor) {
        const [ax, ay] = toScreen(this.error.anchor);
        place(e, ax, ay, ERROR_GAP, box);
      } else {
        e.style.left = e.style.top = e.style.maxWidth = e.style.maxHeight = "";
      }
    }

    const placed = [];
    for (const g of this.groups) {
      let [x, y] = g.anchor ? toScreen(g.anchor) : [NaN, NaN];
      const visible = Number.isFinite(x) && x >= 0 && y >= 0 && x <= W && y <= H;
      g.badge.hidden = !visible;
      if (!visible) {
        g.card.style.visibility = "hidden";
        continue;
      }
      // Badges of features close together on screen are moved apart so both can be tapped.
      for (let k = 0; k < 8 && placed.some(([px, py]) => Math.hypot(px - x, py - y) < BADGE_SPACING); k++) {
        x += BADGE_SPACING;
      }
      placed.push([x, y]);
      g.badge.style.left = `${x}px`;
      g.badge.style.top = `${y}px`;
      g.card.style.visibility = "";
      if (!g.card.hidden) place(g.card, x, y, WARNING_GAP, box);
    }
  }
}

/**
 * Puts `card` (absolutely positioned in the map) beside the anchor (ax, ay): above, below, right
 * or left, the first side where it fits within the map and clear of the zoom buttons, else where
 * it overflows least, then clamped inside the map. Its tail points at the anchor when it can.
 */
function place(card, ax, ay, gap, { W, H, tools }) {
  card.style.maxWidth = `${Math.max(120, Math.min(MAX_CARD_WIDTH, W - 2 * MARGIN))}px`;
  card.style.maxHeight = `${Math.max(60, H - 2 * MARGIN)}px`;
  card.style.left = "0px";
  card.style.top = "0px";
  const w = card.offsetWidth;
  const h = card.offsetHeight;
  const clamp = (v, lo, hi) => Math.max(lo, Math.min(hi, v));
  const hitsTools = (x, y) => x < tools.right && x + w > tools.left && y < tools.bottom && y + h > tools.top;
  const candidates = [
    { side: "above", x: ax - w / 2, y: ay - gap - h },
    { side: "below", x: ax - w / 2, y: ay + gap },
    { side: "right", x: ax + gap, y: ay - h / 2 },
    { side: "left", x: ax - gap - w, y: ay - h / 2 },
  ].map((c) => {
    const vertical = c.side === "above" || c.side === "below";
    if (vertical) {
      c.x = clamp(c.x, MARGIN, W - MARGIN - w);
      // Slide left of the zoom buttons if it would cover them.
      if (hitsTools(c.x, c.y)) c.x = Math.max(MARGIN, tools.left - w);
    } else {
      c.y = clamp(c.y, MARGIN, H - MARGIN - h);
    }
    const overflow =
      Math.max(0, MARGIN - c.x) +
      Math.max(0, c.x + w - (W - MARGIN)) +
      Math.max(0, MARGIN - c.y) +
      Math.max(0, c.y + h - (H - MARGIN));
    c.cost = overflow + (hitsTools(c.x, c.y) ? 40 : 0);
    return c;
  });
  const best = candidates.find((c) => c.cost === 0) ?? candidates.reduce((a, b) => (b.cost < a.cost ? b : a));
  const x = clamp(best.x, MARGIN, Math.max(MARGIN, W - MARGIN - w));
  const y = clamp(best.y, MARGIN, Math.max(MARGIN, H - MARGIN - h));
  card.style.left = `${Math.round(x)}px`;
  card.style.top = `${Math.round(y)}px`;
  // The tail, on the side facing the anchor, only if the card still sits beside the anchor.
  const vertical = best.side === "above" || best.side === "below";
  const along = vertical ? ax - x : ay - y;
  const span = vertical ? w : h;
  const clear = { above: y + h <= ay - 6, below: y >= ay + 6, right: x >= ax + 6, left: x + w <= ax - 6 };
  const beside = along >= 12 && along <= span - 12 && clear[best.side];
  card.dataset.side = best.side;
  card.classList.toggle("tailless", !beside);
  card.style.setProperty("--tail", `${Math.round(clamp(along, 12, span - 12))}px`);
}
