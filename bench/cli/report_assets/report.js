// The script of every page `ocpbench report` writes. Each page loads its data first
// (data/*.js sets window.OCPB_DATA: a <script> file, not a fetch, so that the site works opened
// from disk, where browsers refuse fetch) and then this file, which draws the page named by
// <body data-page>: "index" (a suite), "problem" (one problem) or "compare" (two runs).
// Plain DOM and SVG, no library: the site must work offline and from Debian packages alone.
"use strict";
(function () {
  const D = window.OCPB_DATA;
  const main = document.getElementById("main");
  const SVG = "http://www.w3.org/2000/svg";
  const COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
    "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"];

  // ---- small helpers ----------------------------------------------------------------------

  // An element with attributes and children (strings become text: no HTML from the data).
  function el(tag, attrs, ...kids) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (v === null || v === undefined) continue;
      if (k === "class") e.className = v; else e.setAttribute(k, v);
    }
    for (const kid of kids.flat(Infinity)) {
      if (kid === null || kid === undefined || kid === false) continue;
      e.appendChild(typeof kid === "string" || typeof kid === "number"
        ? document.createTextNode(String(kid)) : kid);
    }
    return e;
  }
  function svgEl(tag, attrs) {
    const e = document.createElementNS(SVG, tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    return e;
  }
  // Numbers as the summaries print them: 4 significant digits, exponent when far from 1.
  function fmt(v) {
    if (v === null || v === undefined || (typeof v === "number" && !isFinite(v))) return "–";
    if (typeof v !== "number") return String(v);
    if (Number.isInteger(v) && Math.abs(v) < 1e7) return String(v);
    const a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(2);
    return String(Number(v.toPrecision(4)));
  }
  function section(title, id, ...kids) {
    return el("section", {id: id}, el("h2", {}, title), ...kids);
  }
  function table(headers, rows, attrs) {
    return el("table", attrs || {},
      el("thead", {}, el("tr", {}, headers.map((h) => el("th", {}, h)))),
      el("tbody", {}, rows.map((r) => el("tr", {}, r.map((c) => el("td", {}, c))))));
  }
  // The page's sections into <main>; a section with nothing to show is null and left out.
  function fill(...sections) { main.append(...sections.filter((x) => x)); }
  function finite(v) { return typeof v === "number" && isFinite(v); }

  // ---- plots --------------------------------------------------------------------------------
  // A line plot in SVG: series {label, x, y, color, step, dash}, horizontal lines {y, label}
  // (bounds), optional log axes. Drag across the plot to zoom into an x range; double-click to
  // zoom out again (trajectories of 400 intervals are easier read closely).

  function niceTicks(lo, hi, log) {
    if (log) {
      const out = [];
      const e0 = Math.floor(Math.log10(lo)), e1 = Math.ceil(Math.log10(hi));
      if (!isFinite(e0) || !isFinite(e1)) return [lo, hi];
      // A range of many decades gets every k-th power of ten, not a crowd of labels.
      const every = Math.max(1, Math.ceil((e1 - e0) / 8));
      for (let e = e0; e <= e1; e += every) {
        const v = Math.pow(10, e);
        if (v >= lo * 0.999 && v <= hi * 1.001) out.push(v);
      }
      return out.length >= 2 ? out : [lo, hi];
    }
    const span = hi - lo || Math.abs(hi) || 1;
    const raw = span / 5;
    const mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => span / s <= 6);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
      out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    }
    return out;
  }

  function extent(values, log) {
    let lo = Infinity, hi = -Infinity;
    for (const v of values) {
      if (!finite(v) || (log && v <= 0)) continue;
      lo = Math.min(lo, v); hi = Math.max(hi, v);
    }
    if (lo === Infinity) return null;
    if (lo === hi) {
      if (log) { lo /= 2; hi *= 2; } else { const d = Math.abs(lo) * 0.1 || 1; lo -= d; hi += d; }
    }
    return [lo, hi];
  }

  function plot(opts) {
    const W = 560, H = 300, L = 64, R = 12, T = 12, B = 40;
    const fig = el("figure", {class: "plot"});
    if (opts.title) fig.appendChild(el("figcaption", {}, opts.title));
    const holder = el("div", {class: "plot-svg"});
    fig.appendChild(holder);
    const legend = el("ul", {class: "legend"});
    opts.series.forEach((s, i) => {
      s.color = s.color || COLORS[i % COLORS.length];
      legend.appendChild(el("li", {}, el("span", {class: "swatch", style: "background:" + s.color}),
        s.label));
    });
    for (const h of opts.hlines || []) {
      legend.appendChild(el("li", {}, el("span", {class: "swatch bound"}), h.label));
    }
    fig.appendChild(legend);
    const allX = opts.series.flatMap((s) => s.x);
    const fullX = extent(allX, opts.logx);
    let view = fullX;

    function draw() {
      holder.textContent = "";
      const svg = svgEl("svg", {viewBox: `0 0 ${W} ${H}`, class: "chart", role: "img"});
      holder.appendChild(svg);
      if (!view) {
        svg.appendChild(svgEl("text", {x: W / 2, y: H / 2, "text-anchor": "middle"})).textContent =
          "no finite values";
        return;
      }
      const [x0, x1] = view;
      const ys = [];
      for (const s of opts.series) {
        s.x.forEach((x, k) => { if (x >= x0 && x <= x1) ys.push(s.y[k]); });
      }
      for (const h of opts.hlines || []) ys.push(h.y);
      // No value to place (a log axis of zeros): an empty frame, never an endless tick loop.
      const ye = extent(ys, opts.logy) || (opts.logy ? [0.1, 1] : [0, 1]);
      const [y0, y1] = ye;
      const tx = (v) => opts.logx ? Math.log10(v) : v;
      const ty = (v) => opts.logy ? Math.log10(v) : v;
      const sx = (v) => L + (tx(v) - tx(x0)) / ((tx(x1) - tx(x0)) || 1) * (W - L - R);
      const sy = (v) => H - B - (ty(v) - ty(y0)) / ((ty(y1) - ty(y0)) || 1) * (H - T - B);
      const axes = svgEl("g", {class: "axes"});
      svg.appendChild(axes);
      axes.appendChild(svgEl("rect", {x: L, y: T, width: W - L - R, height: H - T - B,
        class: "frame"}));
      for (const v of niceTicks(x0, x1, opts.logx)) {
        const x = sx(v);
        axes.appendChild(svgEl("line", {x1: x, x2: x, y1: T, y2: H - B, class: "grid"}));
        const t = svgEl("text", {x: x, y: H - B + 14, "text-anchor": "middle"});
        t.textContent = fmt(v);
        axes.appendChild(t);
      }
      for (const v of niceTicks(y0, y1, opts.logy)) {
        const y = sy(v);
        axes.appendChild(svgEl("line", {x1: L, x2: W - R, y1: y, y2: y, class: "grid"}));
        const t = svgEl("text", {x: L - 4, y: y + 4, "text-anchor": "end"});
        t.textContent = fmt(v);
        axes.appendChild(t);
      }
      const xl = svgEl("text", {x: (L + W - R) / 2, y: H - 6, "text-anchor": "middle",
        class: "label"});
      xl.textContent = opts.xlabel || "";
      axes.appendChild(xl);
      const yl = svgEl("text", {x: 12, y: (T + H - B) / 2, "text-anchor": "middle", class: "label",
        transform: `rotate(-90 12 ${(T + H - B) / 2})`});
      yl.textContent = opts.ylabel || "";
      axes.appendChild(yl);
      const clipId = "clip" + Math.random().toString(36).slice(2);
      const defs = svgEl("defs");
      const clip = svgEl("clipPath", {id: clipId});
      clip.appendChild(svgEl("rect", {x: L, y: T, width: W - L - R, height: H - T - B}));
      defs.appendChild(clip);
      svg.appendChild(defs);
      const data = svgEl("g", {"clip-path": `url(#${clipId})`});
      svg.appendChild(data);
      for (const h of opts.hlines || []) {
        if (!finite(h.y) || (opts.logy && h.y <= 0)) continue;
        data.appendChild(svgEl("line", {x1: L, x2: W - R, y1: sy(h.y), y2: sy(h.y),
          class: "bound"}));
      }
      for (const s of opts.series) {
        let d = "", pen = false;
        for (let k = 0; k < s.x.length; ++k) {
          const x = s.x[k], y = s.y[k];
          const ok = finite(x) && finite(y) && !(opts.logx && x <= 0) && !(opts.logy && y <= 0);
          if (!ok) { pen = false; continue; }
          if (s.step && pen && k > 0) d += `L${sx(x).toFixed(2)},${sy(s.y[k - 1]).toFixed(2)}`;
          d += (pen ? "L" : "M") + sx(x).toFixed(2) + "," + sy(y).toFixed(2);
          pen = true;
        }
        const path = svgEl("path", {d: d, stroke: s.color, fill: "none", "stroke-width": 1.6});
        if (s.dash) path.setAttribute("stroke-dasharray", "5,3");
        data.appendChild(path);
        if (s.x.length === 1 && finite(s.x[0]) && finite(s.y[0])) {
          data.appendChild(svgEl("circle", {cx: sx(s.x[0]), cy: sy(s.y[0]), r: 3, fill: s.color}));
        }
      }
      // Drag to zoom (x only), double-click to reset.
      const band = svgEl("rect", {y: T, height: H - T - B, class: "zoom", width: 0});
      svg.appendChild(band);
      let start = null;
      const toX = (ev) => {
        const r = svg.getBoundingClientRect();
        return (ev.clientX - r.left) * W / r.width;
      };
      svg.addEventListener("mousedown", (ev) => { start = toX(ev); });
      svg.addEventListener("mousemove", (ev) => {
        if (start === null) return;
        const x = toX(ev);
        band.setAttribute("x", Math.min(x, start));
        band.setAttribute("width", Math.abs(x - start));
      });
      svg.addEventListener("mouseup", (ev) => {
        if (start === null) return;
        const a = Math.min(start, toX(ev)), b = Math.max(start, toX(ev));
        start = null;
        if (b - a < 5) { band.setAttribute("width", 0); return; }
        const inv = (px) => {
          const f = (px - L) / (W - L - R);
          const v = tx(x0) + f * (tx(x1) - tx(x0));
          return opts.logx ? Math.pow(10, v) : v;
        };
        view = [inv(Math.max(a, L)), inv(Math.min(b, W - R))];
        draw();
      });
      svg.addEventListener("dblclick", () => { view = fullX; draw(); });
    }
    draw();
    return fig;
  }

  // ---- the index page: a suite --------------------------------------------------------------

  const COLUMNS = [
    {key: "problem", title: "problem", link: true},
    {key: "method", title: "method"},
    {key: "seed", title: "seed", num: true},
    {key: "N", title: "N", num: true},
    {key: "status", title: "status"},
    {key: "warnings", title: "warnings"},
    {key: "tags", title: "tags"},
    {key: "J_fine", title: "J fine", num: true},
    {key: "ref_error", title: "rel. error vs reference", num: true},
    {key: "violation", title: "violation (worst)", num: true},
    {key: "iterations", title: "iterations", num: true},
    {key: "cpu", title: "CPU s", num: true},
    {key: "time_to_target", title: "time to target s", num: true},
  ];
  const ONLINE_COLUMNS = [
    {key: "energy_true", title: "energy true", num: true},
    {key: "offline_energy_true", title: "offline energy true", num: true},
    {key: "cycles", title: "cycles", num: true},
  ];

  function cellText(c, col) {
    const v = c[col.key];
    if (Array.isArray(v)) return v.join(", ");
    return col.num ? fmt(v) : (v === null || v === undefined ? "" : String(v));
  }

  function metaSection(m) {
    const rows = [
      ["suite", m.suite], ["results read", m.source], ["records", String(m.records)],
      ["commits", m.commits.join(", ") || "not recorded"],
      ["versions", m.versions.join("; ") || "not recorded"],
      ["records written", m.recorded_at + " (the records file's last change)"],
      ["machine", m.machine || "not in the records (they carry no host name)"],
    ];
    if (m.shards > 0) {
      const partial = m.expected_cases > m.records
        ? `: partial, ${m.records} of the suite's ${m.expected_cases} cases (ocpbench merge names ` +
          "the missing ones)" : `, all ${m.records} cases of the suite`;
      rows.push(["sharded sweep", `merged from ${m.shards} shards${partial}`]);
    }
    if (m.online) rows.push(["online runs", "yes: re-planning records (kind online)"]);
    if (m.dropped_partial) rows.push(["note", "a last record cut short by a killed run was left out"]);
    return section("What ran", "meta",
      el("dl", {}, rows.map(([k, v]) => [el("dt", {}, k), el("dd", {}, v)])));
  }

  function countsSection(counts) {
    const st = Object.entries(counts.status);
    const wa = Object.entries(counts.warning);
    return section("Counts", "counts", el("div", {class: "row"},
      table(["status", "cases"], st, {id: "status-counts"}),
      wa.length ? table(["warning", "cases"], wa, {id: "warning-counts"})
        : el("p", {}, "No case has a warning.")));
  }

  // rho(tau): each method's fraction of target groups it reached within tau times the best.
  function profilesSection(profiles) {
    if (!profiles.length) return section("Performance profiles", "profiles",
      el("p", {}, "No solve records: no profile."));
    let tmax = 2;
    for (const p of profiles) for (const r of p.ratios) if (finite(r)) tmax = Math.max(tmax, r * 1.5);
    const series = profiles.map((p) => {
      const n = p.ratios.length;
      const finiteR = p.ratios.filter(finite).sort((a, b) => a - b);
      const x = [1], y = [finiteR.filter((r) => r <= 1).length / n];
      let k = y[0] * n;
      for (const r of finiteR) {
        if (r <= 1) continue;
        ++k;
        x.push(r); y.push(k / n);
      }
      x.push(tmax); y.push(k / n);
      return {label: p.method, x: x, y: y, step: true};
    });
    return section("Performance profiles", "profiles",
      el("p", {}, "Dolan-More profiles of CPU time to target (summary.md's rule): the fraction " +
        "of target groups (problem, seed, parameters, terminal form) where a method reached the " +
        "target within tau times the fastest method's time. A method that never reached it " +
        "stays below 1."),
      plot({series: series, logx: true, xlabel: "tau", ylabel: "rho(tau)"}));
  }

  // A case's problem page, its menus set to the case's seed and setting (read by runViews).
  function caseLink(c) {
    return `${c.page}#seed=${encodeURIComponent(c.seed)}&setting=${encodeURIComponent(c.section)}`;
  }

  function casesSection(cases, online) {
    const cols = online ? COLUMNS.concat(ONLINE_COLUMNS) : COLUMNS;
    const filters = [
      {key: "problem", title: "problem"}, {key: "method", title: "method"},
      {key: "status", title: "status"}, {key: "warnings", title: "warning"},
      {key: "N", title: "N"}, {key: "tags", title: "tag"},
    ];
    const bar = el("div", {class: "filters"});
    const selects = {};
    for (const f of filters) {
      const values = new Set();
      for (const c of cases) {
        const v = c[f.key];
        if (Array.isArray(v)) v.forEach((x) => values.add(String(x))); else values.add(String(v));
      }
      const sorted = [...values].sort((a, b) =>
        f.key === "N" ? Number(a) - Number(b) : a.localeCompare(b));
      const s = el("select", {id: "filter-" + f.key, "aria-label": f.title},
        el("option", {value: ""}, "any " + f.title), sorted.map((v) => el("option", {value: v}, v)));
      selects[f.key] = s;
      bar.appendChild(el("label", {}, f.title + " ", s));
    }
    const search = el("input", {id: "filter-text", type: "search", placeholder: "text in the row"});
    bar.appendChild(el("label", {}, "search ", search));
    const shown = el("p", {id: "shown"});
    const head = el("tr", {});
    const tbody = el("tbody", {});
    const tbl = el("table", {id: "cases", class: "cases"}, el("thead", {}, head), tbody);
    let sortKey = null, sortDir = 1;
    cols.forEach((col) => {
      const th = el("th", {"data-key": col.key, class: "sortable", title: "click to sort"},
        col.title);
      th.addEventListener("click", () => {
        sortDir = sortKey === col.key ? -sortDir : 1;
        sortKey = col.key;
        for (const other of head.children) other.removeAttribute("aria-sort");
        th.setAttribute("aria-sort", sortDir > 0 ? "ascending" : "descending");
        render();
      });
      head.appendChild(th);
    });
    function matches(c) {
      for (const f of filters) {
        const want = selects[f.key].value;
        if (!want) continue;
        const v = c[f.key];
        if (Array.isArray(v) ? !v.map(String).includes(want) : String(v) !== want) return false;
      }
      const text = search.value.trim().toLowerCase();
      if (text && !cols.map((col) => cellText(c, col)).join(" ").toLowerCase().includes(text)) {
        return false;
      }
      return true;
    }
    // Missing numbers sort last whichever the direction: "not computed" is never the best.
    function compare(a, b) {
      const col = cols.find((x) => x.key === sortKey);
      const va = a[sortKey], vb = b[sortKey];
      if (col.num) {
        const fa = finite(va), fb = finite(vb);
        if (!fa || !fb) return fa === fb ? 0 : fa ? -1 : 1;
        return sortDir * (va - vb);
      }
      return sortDir * cellText(a, col).localeCompare(cellText(b, col));
    }
    function render() {
      let rows = cases.filter(matches);
      if (sortKey) rows = rows.slice().sort(compare);
      tbody.textContent = "";
      for (const c of rows) {
        const tr = el("tr", {"data-key": c.key, class: "status-" + c.status});
        for (const col of cols) {
          const text = cellText(c, col);
          tr.appendChild(el("td", {class: col.num ? "num" : null},
            col.link ? el("a", {href: caseLink(c)}, text) : text));
        }
        tbody.appendChild(tr);
      }
      shown.textContent = `${rows.length} of ${cases.length} cases shown`;
    }
    for (const s of Object.values(selects)) s.addEventListener("change", render);
    search.addEventListener("input", render);
    render();
    return section("Every case", "every-case",
      el("p", {}, "One row per record. Filter with the menus, sort by a column's title " +
        "(again: the other way). J fine: the common evaluator's cost on the 10x finer grid; " +
        "violation: the worst of the terminal (fine), control, path, state-bound and boundary " +
        "violations; time to target as summary.md defines it."),
      bar, shown, el("div", {class: "scroll"}, tbl));
  }

  // Online re-planning records (kind online) in a table of their own: what they measure is the
  // energy of the executed plan on the true channel against the offline plan's.
  function onlineTableSection(cases) {
    const online = cases.filter((c) => c.kind === "online");
    if (!online.length) return null;
    return section("Online re-planning", "online-runs",
      el("p", {}, "Each online run's executed energy on the true channel against the offline " +
        "plan of t0 = 0 (ratio < 1: re-planning paid)."),
      el("div", {class: "scroll"}, table(["problem", "method", "seed", "status", "energy true",
        "offline energy true", "energy ratio", "transmit energy ratio", "cycles", "CPU s"],
      online.map((c) => [el("a", {href: c.page}, c.problem), c.method, String(c.seed), c.status,
        fmt(c.energy_true), fmt(c.offline_energy_true), fmt(c.energy_ratio),
        fmt(c.transmit_energy_ratio), fmt(c.cycles), fmt(c.cpu)]), {id: "online", class: "cases"})));
  }

  function problemsSection(problems) {
    return section("Problems", "problems", el("ul", {},
      problems.map((p) => el("li", {}, el("a", {href: p.page}, p.name),
        p.description ? " — " + p.description : ""))));
  }

  function figuresSection(figures) {
    if (!figures.length) return null;
    return section("Figures", "figures",
      el("p", {}, "The figures results/plot.py wrote for these results (figures/)."),
      el("div", {class: "gallery"}, figures.map((f) =>
        el("a", {href: "figures/" + f}, el("img", {src: "figures/" + f, alt: f, loading: "lazy"})))));
  }

  function indexPage() {
    document.title = `${D.meta.suite}: OCPBench report`;
    fill(el("h1", {}, `Suite ${D.meta.suite}`),
      metaSection(D.meta), countsSection(D.counts), problemsSection(D.problems),
      profilesSection(D.profiles), onlineTableSection(D.cases), casesSection(D.cases, D.meta.online),
      figuresSection(D.figures));
  }

  // ---- a problem page -------------------------------------------------------------------------

  function runLabel(r) { return `${r.method}, seed ${r.seed}`; }

  // The runs' rows of one matrix (x, u, p: rows of values) against their times, one series each.
  function rowSeries(runs, pick, row) {
    const out = [];
    runs.forEach((r) => {
      const part = pick(r);
      if (!part || !part.m || !part.m[row]) return;
      out.push({label: runLabel(r), x: part.t, y: part.m[row], step: part.step,
        color: r.color});
    });
    return out;
  }

  function boundLines(lower, upper, i) {
    const out = [];
    if (lower && finite(lower[i])) out.push({y: lower[i], label: "lower bound " + fmt(lower[i])});
    if (upper && finite(upper[i])) out.push({y: upper[i], label: "upper bound " + fmt(upper[i])});
    return out;
  }

  // Controls are held over each interval (u_rule); the last sample is repeated to tf so that the
  // step of the last interval is drawn.
  function controls(r) {
    const tr = r.trajectory;
    if (!tr || !tr.u || !tr.u.length) return null;
    const n = tr.u[0].length;
    const held = !tr.u_rule || /constant|left|hold/i.test(tr.u_rule);
    const t = tr.t.slice(0, n);
    const m = tr.u.map((row) => row.slice());
    if (held && tr.t.length > n) {
      t.push(tr.t[n]);
      m.forEach((row) => row.push(row[n - 1]));
    }
    return {t: t, m: m, step: held};
  }

  function trajectorySection(runs, bounds) {
    const kept = runs.filter((r) => r.trajectory);
    if (!kept.length) {
      return section("Trajectories", "trajectories",
        el("p", {}, "No record of this problem keeps its trajectory (the suite's keep_trajectory)."));
    }
    const nx = kept[0].trajectory.x.length, nu = kept[0].trajectory.u.length;
    const figs = [];
    const b = bounds || {};
    const states = (r) => r.trajectory ? {t: r.trajectory.t, m: r.trajectory.x} : null;
    for (let i = 0; i < nx; ++i) {
      figs.push(plot({title: `state x${i + 1}`, xlabel: "t", ylabel: `x${i + 1}`,
        series: rowSeries(runs, states, i), hlines: boundLines(b.x_lower, b.x_upper, i)}));
    }
    for (let i = 0; i < nu; ++i) {
      figs.push(plot({title: `control u${i + 1}`, xlabel: "t", ylabel: `u${i + 1}`,
        series: rowSeries(runs, controls, i), hlines: boundLines(b.u_lower, b.u_upper, i)}));
    }
    const withP = runs.filter((r) => r.costates);
    if (withP.length) {
      const p = (r) => r.costates ? {t: r.costates.t, m: r.costates.p} : null;
      for (let i = 0; i < withP[0].costates.p.length; ++i) {
        figs.push(plot({title: `costate p${i + 1}`, xlabel: "t", ylabel: `p${i + 1}`,
          series: rowSeries(runs, p, i)}));
      }
    }
    return section("Trajectories, controls and costates", "trajectories",
      el("p", {}, "Each method's trajectory as its record keeps it (the common evaluator's " +
        "states on the method's grid), controls held over each interval, and the method's own " +
        "costates where it has them. Bounds are drawn grey and dashed" +
        (bounds ? "." : " where the registry knows the problem (it does not know this one).") +
        " Drag across a plot to zoom in; double-click to zoom out."),
      el("div", {class: "plots"}, figs));
  }

  // Convergence: the gap of each iterate's own objective to the best final J of its target
  // group (summary.md's target), against iteration and against CPU seconds.
  function convergenceSection(runs) {
    const byIter = [], byCpu = [];
    runs.forEach((r) => {
      const h = (r.history || []).filter((e) => e.intervals === undefined || e.intervals === null);
      if (!h.length || !finite(r.best_J)) return;
      const scale = Math.max(Math.abs(r.best_J), 1e-12);
      const gap = h.map((e) => finite(e.J) ? Math.max(Math.abs(e.J - r.best_J) / scale, 1e-16) : null);
      const color = r.color;
      byIter.push({label: runLabel(r), x: h.map((e) => e.iteration), y: gap, color: color});
      byCpu.push({label: runLabel(r), x: h.map((e) => e.cpu_seconds), y: gap, color: color});
    });
    if (!byIter.length) {
      return section("Convergence", "convergence", el("p", {}, "No record of this problem has an " +
        "iteration history."));
    }
    const target = [{y: 0.01, label: "1 % (the target)"}];
    return section("Convergence", "convergence",
      el("p", {}, "|J - best J| / |best J| of each iterate (J: the method's own objective; " +
        "best J: the lowest final J fine of the target group), against iteration and CPU time."),
      el("div", {class: "plots"},
        plot({series: byIter, logy: true, xlabel: "iteration", ylabel: "gap to best J",
          hlines: target}),
        plot({series: byCpu, logy: true, xlabel: "CPU s", ylabel: "gap to best J",
          hlines: target})));
  }

  function meshSection(runs) {
    const refined = runs.filter((r) => r.mesh && r.mesh.history && r.mesh.history.length);
    if (!refined.length) return null;
    const blocks = refined.map((r) => el("div", {},
      el("h3", {}, runLabel(r), ` (stopped: ${r.mesh.stop_reason || "–"})`),
      table(["mesh", "intervals", "NLP variables", "NLP constraints", "max error", "iterations",
        "CPU s", "status"],
      r.mesh.history.map((m, k) => [String(k + 1), fmt(m.intervals), fmt(m.nlp_variables),
        fmt(m.nlp_constraints), fmt(m.max_error), fmt(m.iterations), fmt(m.cpu_seconds),
        m.status || ""]), {class: "mesh"})));
    const series = refined.map((r) => ({label: runLabel(r),
      x: r.mesh.history.map((m) => m.intervals), y: r.mesh.history.map((m) => m.max_error),
      color: r.color}));
    return section("Mesh refinement", "mesh",
      plot({series: series, logy: true, xlabel: "mesh intervals", ylabel: "max error estimate"}),
      blocks);
  }

  function warningsSection(runs) {
    const items = [];
    for (const r of runs) {
      for (const w of r.warning_messages) {
        items.push(el("li", {}, el("strong", {}, runLabel(r)), ` — ${w.code}: ${w.message}`));
      }
    }
    return section("Warnings", "warnings", items.length ? el("ul", {}, items)
      : el("p", {}, "No record of this problem has a warning."));
  }

  // Online records: the executed path against the offline plan (records with keep_trajectory)
  // and each re-planning cycle's solve time.
  function onlineSection(runs) {
    const paths = [], solves = [];
    runs.forEach((r) => {
      const color = r.color;
      for (const [part, dash] of [["online_executed", false], ["online_offline", true]]) {
        const p = r[part];
        if (!p || !p.x || p.x.length < 2) continue;
        const what = part === "online_executed" ? "executed" : "offline plan";
        paths.push({label: `${runLabel(r)}, ${what}`, x: p.x[0], y: p.x[1], dash: dash,
          color: color});
      }
      const cycles = r.online_cycles || [];
      if (cycles.length) {
        solves.push({label: runLabel(r), x: cycles.map((c) => c.t0),
          y: cycles.map((c) => c.solve_seconds), color: color});
      }
    });
    if (!paths.length && !solves.length) return null;
    return section("Online re-planning", "online", el("div", {class: "plots"},
      paths.length ? plot({title: "path: executed (solid) and offline plan (dashed)",
        series: paths, xlabel: "x1", ylabel: "x2"}) : null,
      solves.length ? plot({title: "each cycle's re-planning solve", series: solves,
        xlabel: "cycle start t0", ylabel: "solve seconds"}) : null));
  }

  // Every judged number of each run, one row per run.
  function sideBySideSection(runs) {
    const online = runs.some((r) => r.kind === "online");
    const rows = table(["method", "seed", "N", "terminal", "status", "solver status",
      "J fine", "Jbar fine", "rel. error vs ref.", "terminal viol. fine", "control viol.",
      "path viol.", "discretization gap", "costate error", "iterations", "CPU s",
      "time to target s", "warnings"].concat(online
      ? ["energy true", "offline energy true", "energy ratio", "cycles"] : []),
    runs.map((r) => [el("span", {}, el("span", {class: "swatch", style: "background:" + r.color}),
      r.method), String(r.seed), String(r.N), r.terminal, r.status, r.solver_status,
      fmt(r.J_fine), fmt(r.Jbar_fine), fmt(r.ref_error), fmt(r.terminal_violation_fine),
      fmt(r.control_violation), fmt(r.path_violation), fmt(r.discretization_gap),
      fmt(r.costate_error), fmt(r.iterations), fmt(r.cpu), fmt(r.time_to_target),
      r.warnings.join(", ")].concat(online ? [fmt(r.energy_true), fmt(r.offline_energy_true),
      fmt(r.energy_ratio), fmt(r.cycles)] : [])), {id: "methods", class: "cases"});
    return section("Methods side by side", "side-by-side", el("div", {class: "scroll"}, rows));
  }

  function problemPage() {
    document.title = `${D.problem}: OCPBench report`;
    const refs = D.references.map((r) => [fmt(r.value), r.quantity, r.scheme === "continuous"
      ? "continuous" : `${r.scheme}, N = ${r.N}`, r.source]);
    const runs = D.runs;
    runs.forEach((r, i) => { r.color = COLORS[i % COLORS.length]; });
    fill(el("p", {}, el("a", {href: "index.html"}, `← suite ${D.suite}`)),
      el("h1", {}, D.problem),
      section("The problem", "problem",
        el("p", {}, D.description),
        D.origin ? el("p", {}, "Origin: " + D.origin) : null,
        D.tags.length ? el("p", {}, "Tags: " + D.tags.join(", ")) : null,
        D.hamiltonian_note ? el("p", {}, "Hamiltonian descent: " + D.hamiltonian_note) : null,
        refs.length ? table(["reference", "quantity", "optimum of", "source"], refs)
          : el("p", {}, "No published reference value.")),
      runViews(runs));
  }

  // The problem's warnings, then the runs' table and figures for the runs the menus pick (a seed,
  // a setting) when there are several: fifty curves of five seeds overlaid tell nothing, and 160 rows hide the one wanted.
  // The first seed and setting are shown first; every run keeps its colour whichever are shown.
  function runViews(runs) {
    const seeds = [...new Set(runs.map((r) => String(r.seed)))];
    const sections = [...new Set(runs.map((r) => r.section))];
    const holder = el("div", {id: "runs"});
    const menus = el("div", {class: "filters"});
    const pick = {};
    const menu = (key, title, values, first) => {
      if (values.length < 2) return;
      const s = el("select", {id: "runs-" + key, "aria-label": title},
        el("option", {value: ""}, "every " + title), values.map((v) => el("option", {value: v}, v)));
      s.value = first;
      s.addEventListener("change", draw);
      pick[key] = s;
      menus.appendChild(el("label", {}, "show " + title + " ", s));
    };
    // A link from the index's table names the case's seed and setting (#seed=S&setting=X).
    const asked = new URLSearchParams(window.location.hash.slice(1));
    const first = (values, key) => values.includes(asked.get(key)) ? asked.get(key) : values[0];
    menu("seed", "seed", seeds, first(seeds, "seed"));
    menu("section", "setting", sections, first(sections, "setting"));
    function draw() {
      const shown = runs.filter((r) =>
        (!pick.seed || !pick.seed.value || String(r.seed) === pick.seed.value) &&
        (!pick.section || !pick.section.value || r.section === pick.section.value));
      holder.textContent = "";
      holder.append(...[sideBySideSection(shown), trajectorySection(shown, D.bounds), convergenceSection(shown), meshSection(shown),
        onlineSection(shown)].filter((x) => x));
    }
    draw();
    const note = menus.children.length ? el("p", {}, `${runs.length} runs of this problem; the ` +
      "menus choose which the tables and figures below show.") : null;
    // Every warning of the problem, whatever the menus show.
    return el("div", {}, warningsSection(runs), note, menus.children.length ? menus : null,
      holder);
  }

  // ---- the compare page: two runs of one suite ------------------------------------------------

  // The CPU verdict of a case or method in words: `compare`'s finding when it made one, else
  // why it made none (inside the ratio threshold, or beyond it without a significant test).
  function cpuVerdict(item) {
    const f = item.findings.find((x) => x.measure === "CPU");
    if (f) return (f.worse ? "slower" : "faster") + ", significant";
    const r = item.cpu_ratio, t = D.thresholds.cpu_ratio;
    if (!finite(r)) return "–";
    if (r > t || r < 1 / t) return `beyond ${t}x, not significant at alpha = ${D.thresholds.alpha}`;
    return `within ${t}x`;
  }

  // Regressions first, then cases of BASE missing from NEW (a regression too: their result is
  // unknown), improvements, the rest: the order `ocpbench compare` reports them in.
  function comparePage() {
    document.title = `compare ${D.base.suite}: OCPBench report`;
    const rank = {regressed: 0, improved: 2, unchanged: 3};
    const rows = D.cases.map((c) => ({c: c, rank: rank[c.verdict] ?? 3}));
    for (const u of D.only_in_base) rows.push({u: u, rank: 1, verdict: "missing in NEW"});
    rows.sort((a, b) => a.rank - b.rank);
    const v = D.verdict;
    const head = el("dl", {},
      el("dt", {}, "BASE"), el("dd", {}, `${D.base.path} (${D.base.records} records, commits ` +
        `${D.base.commits.join(", ")})`),
      el("dt", {}, "NEW"), el("dd", {}, `${D.new.path} (${D.new.records} records, commits ` +
        `${D.new.commits.join(", ")})`),
      el("dt", {}, "verdict"), el("dd", {id: "verdict"}, v.regression
        ? `regression: ${v.regressed_cases} cases regressed, ${v.regressed_methods} methods' CPU ` +
          `regressed, ${v.only_in_base} cases of BASE missing from NEW`
        : "no regression beyond the thresholds"),
      el("dt", {}, "improved"), el("dd", {}, String(v.improved_cases)),
      el("dt", {}, "overall CPU ratio"), el("dd", {}, fmt(v.overall_cpu_ratio) +
        " (the geometric mean of every case's NEW/BASE: a shift every method shares is usually " +
        "the machine's)"),
      el("dt", {}, "thresholds"), el("dd", {}, Object.entries(D.thresholds)
        .map(([k, x]) => `${k} = ${x}`).join(", ")));
    const tbl = table(["verdict", "section", "method", "seed", "findings", "status", "cost change",
      "CPU ratio", "CPU p-value", "CPU verdict", "time to target s"],
    rows.map((r) => {
      if (r.u) return [r.verdict, r.u.section, r.u.method, "", "not in NEW", r.u.status + " → ?",
        "", "", "", "", ""];
      const c = r.c;
      const findings = c.findings.map((f) => `${f.worse ? "worse" : "better"} ${f.measure}: ${f.detail}`);
      return [c.verdict, c.section, c.method, String(c.seed), findings.join("; "),
        `${c.base.status} → ${c.new.status}`,
        finite(c.cost_change) ? fmt(100 * c.cost_change) + " %" : "–",
        fmt(c.cpu_ratio), fmt(c.cpu_test && c.cpu_test.p_value), cpuVerdict(c),
        `${fmt(c.base.time_to_target)} → ${fmt(c.new.time_to_target)}`];
    }), {id: "compare-cases", class: "cases"});
    tbl.querySelectorAll("tbody tr").forEach((tr, k) => {
      tr.className = "verdict-" + (rows[k].c ? rows[k].c.verdict : "missing");
    });
    const methods = table(["section", "method", "cases", "regressed", "improved",
      "CPU ratio (geometric mean)", "CPU p-value (stratified)", "CPU verdict", "findings"],
    D.methods.map((m) => [m.section, m.method, String(m.cases), String(m.regressed),
      String(m.improved), fmt(m.cpu_ratio), fmt(m.cpu_test && m.cpu_test.p_value), cpuVerdict(m),
      m.findings.map((f) => `${f.worse ? "worse" : "better"} ${f.measure}: ${f.detail}`)
        .join("; ")]), {id: "compare-methods", class: "cases"});
    const profiles = table(["method", "groups"].concat(D.profiles.length
      ? D.profiles[0].tau.map((t) => `tau = ${t}`) : []),
    D.profiles.map((p) => [p.method, String(p.groups)].concat(
      p.base.map((b, k) => `${fmt(b)} → ${fmt(p.new[k])}`))));
    fill(el("p", {}, el("a", {href: "index.html"}, `← suite ${D.new.suite} (NEW)`)),
      el("h1", {}, `Compare: ${D.base.suite}`),
      section("The two runs", "sides", head),
      section("Cases, regressions first", "compare",
        el("p", {}, "As `ocpbench compare` decides them: a CPU ratio is a finding only when it " +
          "passes the ratio threshold and the Mann-Whitney test of the timing repeats rejects " +
          "\"same distribution\" at alpha."),
        el("div", {class: "scroll"}, tbl)),
      section("Methods", "methods", el("div", {class: "scroll"}, methods)),
      D.only_in_new.length ? section("Only in NEW", "only-in-new", table(["section", "method",
        "status"], D.only_in_new.map((u) => [u.section, u.method, u.status]))) : null,
      section("Performance profiles, BASE → NEW", "compare-profiles", profiles));
  }

  const pages = {index: indexPage, problem: problemPage, compare: comparePage};
  pages[document.body.dataset.page]();
  document.body.dataset.ready = "true";
})();
