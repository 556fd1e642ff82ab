// The plan in words: its figures (the summary's rows, each with the member it shows) and the
// panel's list of warnings and the error.
import { formatNumber, ui } from "./app.js";
import { sentence } from "./notes.js";

/**
 * The figures of the plan. Each row's `dd` carries `data-key`, the summary member it shows, and
 * `data-value`, its number as the planner gave it (for tests and for copying).
 */
export function renderSummary(s, options, callMs) {
  const num = (v) => (!Number.isFinite(v) || Math.abs(v) < 1e-9 ? 0 : v); // no "-0"
  const km = (m) => `${formatNumber(num(m) / 1000, 2)} km`;
  const ha = (m2) => `${formatNumber(num(m2) / 10000, 2)} ha`;
  // Small areas (corners a pass cannot reach) in square metres, where 0.00 ha would hide them.
  const area = (m2) => (num(m2) >= 1000 ? ha(m2) : `${formatNumber(num(m2), 0)} m²`);
  const swaths =
    s.dropped_swath_count > 0 ? `${s.swath_count} (${s.dropped_swath_count} too short, left out)` : `${s.swath_count}`;
  const bearing = `${formatNumber(s.bearing_deg ?? 0, 1)}°${options.bearing == null ? " (auto)" : ""}`;
  const classes = s.obstacle_classes ?? {};
  const classCount = ["A", "B", "C", "D"].reduce((n, c) => n + (classes[c] ?? 0), 0);
  const rows = [
    ["Swaths", swaths, { key: "swath_count" }],
    ["Turns", s.turn_count, { key: "turn_count" }],
    ["Blocks", s.block_count, { key: "block_count" }],
    [
      "Decomposition",
      decompositionText(s.decomposition),
      { key: "decomposition", title: s.decomposition?.reason ?? "" },
    ],
    [
      "Headland passes",
      `${s.headland_passes ?? 0}${options.headlandPasses === "auto" || options.headlandPasses === "all" ? ` (${options.headlandPasses})` : ""}`,
      {
        key: "headland_passes",
        title: "Passes around the field; auto: as many as the machine's turns between neighbouring swaths need; all: as many as the field holds",
      },
    ],
    ["Working distance", km(s.working_distance_m), { key: "working_distance_m" }],
    ["Turning distance", km(s.turning_distance_m), { key: "turning_distance_m" }],
    [
      "Turn forms",
      Object.entries(s.turn_forms ?? {})
        .map(([form, n]) => `${n} ${form}`)
        .join(", ") || "none",
      { key: "turn_forms", title: "The drivable turns between swaths, by form" },
    ],
    ...(num(s.turns_outside_field) > 0
      ? [
          [
            "Turns outside the field",
            s.turns_outside_field,
            { key: "turns_outside_field", title: "No turn the machine can drive fits the headland there (see the warnings)" },
          ],
        ]
      : []),
    ...(num(s.connections_outside_field) > 0
      ? [
          [
            "Connections outside the field",
            s.connections_outside_field,
            { key: "connections_outside_field", title: "No turn the machine can drive onto, off or along the headland passes keeps in there (see the warnings)" },
          ],
        ]
      : []),
    ["Connections", km(s.connection_distance_m), { key: "connection_distance_m" }],
    ["Total distance", km(s.total_distance_m), { key: "total_distance_m", cls: "total" }],
    ...(s.coverage
      ? [
          [
            "Field covered",
            `${formatNumber(num(s.coverage.coverage_ratio) * 100, 1)} % of ${formatNumber(num(s.coverage.reachable_ratio) * 100, 1)} % reachable`,
            {
              key: "coverage",
              cls: "total",
              title: "The field worked by the implement, and the most a strip of its width can reach (the parts left standing are drawn in violet)",
            },
          ],
          [
            "Left standing",
            area(s.coverage.uncovered_area_m2),
            { key: "uncovered_area_m2", title: "Crop no working stretch covers" },
          ],
          [
            "Worked twice",
            `${formatNumber(num(s.coverage.overlap_ratio) * 100, 1)} %`,
            { key: "overlap_ratio", title: "Area worked twice or more, over the field area" },
          ],
          ...(num(s.coverage.outside_area_m2) > 0
            ? [
                [
                  "Worked outside",
                  area(s.coverage.outside_area_m2),
                  {
                    key: "outside_area_m2",
                    title: "The implement's strip past the boundary or over an obstacle (outer swaths of a field without headland along a side not parallel to them)",
                  },
                ],
              ]
            : []),
        ]
      : []),
    ["Field area", ha(s.field_area_m2), { key: "field_area_m2" }],
    ["Headland area", ha(s.headland_area_m2), { key: "headland_area_m2" }],
    [
      "Uncovered headland",
      area(s.uncovered_headland_area_m2),
      { key: "uncovered_headland_area_m2", title: "Headland no pass covers: rounded corners, necks too narrow to turn in" },
    ],
    ["Inner field", ha(s.inner_field_area_m2), { key: "inner_field_area_m2" }],
    [
      "Remaining area",
      `${formatNumber(num(s.remaining_area_ratio) * 100, 1)} %`,
      { key: "remaining_area_ratio", title: "Inner field over field area: the share left for swaths" },
    ],
    ["Obstacle classes", classCount ? classTags(classes) : "none", { key: "obstacle_classes" }],
    ...(num(s.lifted_distance_m) > 0 || classes.A > 0
      ? [["Implement lifted", `${formatNumber(num(s.lifted_distance_m), 0)} m`, { key: "lifted_distance_m" }]]
      : []),
    ["Swath bearing", bearing, { key: "bearing_deg" }],
    [
      "Direction",
      directionText(s.direction),
      { key: "direction", title: "How the direction was chosen, and the cost of the plan's swaths" },
    ],
    [
      "Inner field by swaths",
      `${formatNumber(num(s.objectives?.coverage) * 100, 2)} %`,
      { key: "objectives", title: "Share of the inner field the swaths' strips cover" },
    ],
    [
      "Estimated time",
      duration(s.estimated_time_s),
      { key: "estimated_time_s", title: "Swaths and headland at working speed, turns and connections at turning speed" },
    ],
    [
      "Planning time",
      `${formatNumber(s.planning_ms ?? 0, 2)} ms`,
      { key: "planning_ms", title: `${formatNumber(callMs, 2)} ms with the GeoJSON conversion` },
    ],
  ];
  ui.summary.replaceChildren(
    ...rows.flatMap(([label, value, { key, cls, title }]) => {
      const dt = document.createElement("dt");
      const dd = document.createElement("dd");
      dt.textContent = label;
      if (value instanceof Node) dd.append(value);
      else dd.textContent = String(value ?? "–");
      dd.dataset.key = key;
      const raw = s[key];
      dd.dataset.value = typeof raw === "object" && raw !== null ? JSON.stringify(raw) : String(raw ?? "");
      if (cls) dt.className = dd.className = cls;
      if (title) dt.title = dd.title = title;
      return [dt, dd];
    }),
  );
}

/** "Direction per block, 3 directions" with the candidates' times for auto. */
export function decompositionText(d) {
  if (!d) return "–";
  const names = {
    none: "One direction",
    boustrophedon: "Cells, one direction",
    "split-merge": "Direction per block",
  };
  const chosen = d.candidates?.find((c) => c.method === d.method);
  const directions = chosen ? chosen.bearings_deg.length : 1;
  let text = `${names[d.method] ?? d.method}${directions > 1 ? `, ${directions} directions` : ""}`;
  if (d.requested === "auto" && d.candidates?.length > 1) {
    const others = d.candidates
      .filter((c) => c.method !== d.method)
      .map((c) => `${names[c.method] ?? c.method} ${duration(c.estimated_time_s)}`);
    text += ` (fastest; ${others.join(", ")})`;
  }
  return text;
}

/** How the direction was chosen, in words: "searched, 36 directions (coarse to fine)". */
export function directionText(d) {
  if (!d) return "–";
  switch (d.mode) {
    case "search":
      return `searched, ${d.evaluations} directions (${d.method === "brute-force" ? "every degree" : "coarse to fine"})`;
    case "fixed":
      return "as given";
    case "reference":
      return "along the reference";
    default:
      return "along the longest edge";
  }
}

/** Seconds as "1 h 05 min" or "12 min". */
export function duration(seconds) {
  const min = Math.round((Number.isFinite(seconds) ? seconds : 0) / 60);
  return min >= 60 ? `${Math.floor(min / 60)} h ${String(min % 60).padStart(2, "0")} min` : `${min} min`;
}

/** "A1 B1 C2 D1", each class in the tag the map labels obstacles with. */
export function classTags(classes) {
  const out = document.createDocumentFragment();
  for (const c of ["A", "B", "C", "D"]) {
    const tag = document.createElement("span");
    tag.className = "class-tag";
    tag.dataset.class = c;
    tag.textContent = c;
    out.append(tag, String(classes[c] ?? 0));
  }
  return out;
}

/** The panel's list: every warning (those on a feature are on the map too), and the error. */
export function renderWarnings(warnings, error) {
  const item = (text, code, feature, cls) => {
    const li = document.createElement("li");
    li.textContent = text;
    li.title = code;
    li.dataset.code = code;
    if (Number.isInteger(feature)) li.dataset.feature = String(feature);
    if (cls) li.className = cls;
    return li;
  };
  const items = warnings.map((w) => item(sentence(w.message ?? w.code), w.code, w.feature));
  if (error) items.push(item(error.text, error.code, error.feature, "error"));
  ui.warnings.replaceChildren(...items);
}
