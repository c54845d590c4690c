// The commissioning page: every number it shows comes from eigenrad-runtime compiled to
// WebAssembly (eigenrad_web.wasm, built from examples/web/src); this script only moves
// inputs in, draws the answers and writes them out. See examples/web/src/lib.rs for the
// calling convention: inputs are written into buffers the module lends, answers read from
// its memory (f64 values, RGB colours, UTF-8 text).
"use strict";

const page = (() => {
  let wasm = null;        // the module's exports
  let info = null;        // what the open basis holds (JSON from `open`)
  let fileName = "";
  let zone = -1;          // the zone on the plan
  let sky = null;         // the sky state set last (JSON from set_sky_*), or null
  let updates = 0;        // count of redraws, for the tests
  const $ = (id) => document.getElementById(id);

  // ---- the module's memory -------------------------------------------------------------
  const text = () => new TextDecoder().decode(
    new Uint8Array(wasm.memory.buffer, wasm.text_ptr(), wasm.text_len()));
  const values = (n) => new Float64Array(wasm.memory.buffer, wasm.values_ptr(), n);
  const colours = (n) => new Uint8Array(wasm.memory.buffer, wasm.colours_ptr(), 3 * n);
  function check(status) {
    if (status < 0) throw new Error(text());
    return status;
  }

  async function load() {
    const bytes = await (await fetch("eigenrad_web.wasm")).arrayBuffer();
    const { instance } = await WebAssembly.instantiate(bytes, {});
    wasm = instance.exports;
    setStatus("Open a basis file (eigenrad build … -o ROOM.basis).");
  }

  function setStatus(message, error) {
    $("status").textContent = message;
    $("status").className = error ? "error" : "";
  }

  // ---- opening a basis -----------------------------------------------------------------
  function open(name, buffer) {
    const data = new Uint8Array(buffer);
    const ptr = wasm.input_bytes(data.length);
    new Uint8Array(wasm.memory.buffer, ptr, data.length).set(data);
    if (wasm.open() < 0) {
      setStatus(`${name}: ${text()}`, true);
      return false;
    }
    info = JSON.parse(text());
    fileName = name;
    sky = null;
    $("solution").textContent = "";
    $("sun").textContent = "";
    const z = info.zones.findIndex((z) => z.grid && z.name === "work_plane");
    zone = z >= 0 ? z : info.zones.findIndex((z) => z.grid);
    setStatus(`${name}: ${(info.bytes / 1024).toFixed(1)} KiB, ${info.patches} patches, ` +
      `${info.modes} modes (${info.precision}, ${info.formulation}), ${info.channels.length} channels, ` +
      `${info.sensors.length} sensors, ${info.zones.length} zones` +
      (info.daylight ? `, daylight at ${info.daylight.latitude.toFixed(2)}° N ${info.daylight.longitude.toFixed(2)}° E ` +
        `(${info.daylight.sky_patches} sky patches, ${info.daylight.sun_nodes} sun nodes)` : ", no daylight"));
    build();
    $("room").hidden = false;
    refresh();
    return true;
  }

  async function openFile(file) {
    open(file.name, await file.arrayBuffer());
  }

  // ---- the controls --------------------------------------------------------------------
  function options(select, list, chosen) {
    select.replaceChildren(...list.map(([value, label]) => {
      const o = document.createElement("option");
      o.value = value;
      o.textContent = label;
      return o;
    }));
    if (chosen !== undefined) select.value = String(chosen);
  }

  function build() {
    const gridZones = info.zones.map((z, i) => [i, z]).filter(([, z]) => z.grid);
    options($("zone"), gridZones.map(([i, z]) => [i, z.name]), zone);
    options($("target-zone"), info.zones.map((z, i) => [i, z.name]), Math.max(zone, 0));
    options($("target-sensor"), [[-1, "none"], ...info.sensors.map((s, i) => [i, s.name])],
      info.sensors.length ? 0 : -1);

    const table = $("channels");
    table.replaceChildren();
    const head = table.insertRow();
    for (const h of ["channel", "level", "", "DALI arc", "controlled", "W at 1"]) {
      const th = document.createElement("th");
      th.textContent = h;
      head.appendChild(th);
    }
    info.channels.forEach((ch, c) => {
      const row = table.insertRow();
      row.dataset.channel = ch.name;
      row.insertCell().textContent = ch.name;
      const slider = Object.assign(document.createElement("input"),
        { type: "range", min: 0, max: 1, step: 0.001, value: 1, id: `level-${c}` });
      slider.addEventListener("input", () => setLevel(c, Number(slider.value)));
      row.insertCell().appendChild(slider);
      row.insertCell().className = "level";
      const arc = Object.assign(document.createElement("input"),
        { type: "number", min: 0, max: 254, step: 1, id: `arc-${c}` });
      arc.addEventListener("change", () => setArc(c, Number(arc.value)));
      row.insertCell().appendChild(arc);
      const controlled = Object.assign(document.createElement("input"),
        // A channel named `window` is daylight standing in as a channel, not a luminaire (the
        // firmware's controller has the same rule).
        { type: "checkbox", checked: ch.name !== "window", id: `controlled-${c}` });
      row.insertCell().appendChild(controlled);
      const watts = Object.assign(document.createElement("input"),
        { type: "number", min: 0, step: "any", value: 30, id: `watts-${c}` });
      row.insertCell().appendChild(watts);
    });

    $("daylight-panel").hidden = !info.daylight;
    if (info.daylight) {
      const m = info.daylight.utc_offset_minutes;
      const sign = m < 0 ? "−" : "+";
      const a = Math.abs(m);
      $("sky-offset").textContent = `UTC${sign}${String(Math.floor(a / 60)).padStart(2, "0")}:${String(a % 60).padStart(2, "0")} (the site's standard time)`;
      $("sky-model").value = "off";
    }
    skyFields();
  }

  function setLevel(c, level) {
    check(wasm.set_level(c, level));
    refresh(c);
  }

  function setArc(c, arc) {
    check(wasm.set_arc(c, arc));
    refresh();
  }

  // ---- daylight ------------------------------------------------------------------------
  function skyFields() {
    const model = $("sky-model").value;
    const perez = model.startsWith("perez");
    $("sky-type-field").hidden = model !== "cie:other";
    $("water-field").hidden = !perez;
    const unit = model === "perez-w" ? "W/m²" : "lux";
    $("dhi-unit").textContent = unit;
    $("dni-unit").textContent = unit;
  }

  function setSky() {
    const model = $("sky-model").value;
    if (model === "off") {
      check(wasm.clear_sky());
      sky = null;
      $("sun").textContent = "";
      refresh();
      return;
    }
    const [y, mo, d] = $("sky-date").value.split("-").map(Number);
    const [h, mi] = $("sky-time").value.split(":").map(Number);
    const minute = h * 60 + mi;
    const dhi = Number($("sky-dhi").value);
    const dni = Number($("sky-dni").value);
    let status;
    if (model.startsWith("cie")) {
      const type = model === "cie:other" ? Number($("sky-type").value) : Number(model.slice(4));
      status = wasm.set_sky_cie(type, y, mo, d, minute, dhi, dni);
    } else {
      status = wasm.set_sky_perez(model === "perez-lux" ? 1 : 0, y, mo, d, minute, dni, dhi,
        Number($("sky-water").value));
    }
    if (status < 0) {
      $("sun").textContent = text();
      $("sun").className = "error";
      return;
    }
    sky = JSON.parse(text());
    sky.model = $("sky-model").selectedOptions[0].textContent;
    sky.time = `${$("sky-date").value}T${$("sky-time").value}`;
    $("sun").className = "";
    $("sun").textContent = `Sun ${sky.altitude.toFixed(1)}° up, azimuth ${sky.azimuth.toFixed(1)}° ` +
      `(from north, clockwise); diffuse horizontal ${sky.diffuse_horizontal.toFixed(0)} lux, ` +
      `direct normal ${sky.direct_normal.toFixed(0)} lux, global horizontal ${sky.global_horizontal.toFixed(0)} lux.`;
    refresh();
  }

  // ---- readings ------------------------------------------------------------------------
  const fmt = (x, d = 1) => (x === null || !Number.isFinite(x) ? "–" : x.toFixed(d));

  function readings() {
    const n = check(wasm.readings());
    const v = values(3 * n);
    const list = [];
    info.sensors.forEach((s, i) => list.push({ kind: "sensor", name: s.name,
      total: v[3 * i], electric: v[3 * i + 1], daylight: v[3 * i + 2] }));
    const ns = info.sensors.length;
    info.zones.forEach((z, i) => list.push({ kind: "zone", name: z.name,
      total: v[3 * (ns + i)], electric: v[3 * (ns + i) + 1], daylight: v[3 * (ns + i) + 2] }));
    return list;
  }

  function levels() {
    const n = check(wasm.levels());
    const v = values(2 * n);
    return info.channels.map((ch, c) => ({ channel: ch.name, level: v[2 * c],
      arc: v[2 * c + 1] < 0 ? null : v[2 * c + 1] }));
  }

  function showReadings(list) {
    const table = $("readings");
    table.replaceChildren();
    const head = table.insertRow();
    const cols = sky ? ["", "total", "electric", "daylight"] : ["", "lux"];
    for (const h of cols) {
      const th = document.createElement("th");
      th.textContent = h;
      head.appendChild(th);
    }
    for (const r of list) {
      const row = table.insertRow();
      row.dataset.output = `${r.kind}:${r.name}`;
      row.insertCell().textContent = `${r.kind} ${r.name}`;
      for (const part of sky ? ["total", "electric", "daylight"] : ["total"]) {
        const cell = row.insertCell();
        cell.className = part;
        cell.dataset.value = String(r[part]);
        cell.textContent = fmt(r[part]);
      }
    }
  }

  function showLevels(list, except) {
    list.forEach((l, c) => {
      const row = $("channels").rows[c + 1];
      row.cells[2].textContent = `${fmt(100 * l.level)} %`;
      row.cells[2].dataset.value = String(l.level);
      if (c !== except) $(`level-${c}`).value = String(Math.min(1, l.level));
      $(`arc-${c}`).value = l.arc === null ? "" : String(l.arc);
    });
  }

  // ---- the plan ------------------------------------------------------------------------
  function planData() {
    if (zone < 0) return null;
    const n = check(wasm.plan(zone));
    const v = values(8 + n + 1);
    const data = { figures: Array.from(v.subarray(0, 4)), scale: { min: v[4], max: v[5], step: v[6], bin: v[7] },
      values: Array.from(v.subarray(8, 8 + n)), colours: Uint8Array.from(colours(n)), isolux: [] };
    const levelsAt = 8 + n;
    const count = v[levelsAt];
    // The isolux lines follow; read them from a view of the right length.
    let k = levelsAt + 1;
    const all = () => new Float64Array(wasm.memory.buffer, wasm.values_ptr());
    const w = all();
    for (let i = 0; i < count; i++) {
      const level = w[k]; const lines = w[k + 1]; k += 2;
      const polylines = [];
      for (let j = 0; j < lines; j++) {
        const m = w[k]; k += 1;
        const line = [];
        for (let p = 0; p < m; p++) { line.push([w[k], w[k + 1]]); k += 2; }
        polylines.push(line);
      }
      data.isolux.push({ level, polylines });
    }
    return data;
  }

  function frame() {
    const g = info.zones[zone].grid;
    const [lo, hi] = info.extent;
    const margin = 28;
    const cells = $("plan-cells");
    const sx = (cells.width - 2 * margin) / (hi[0] - lo[0] || 1);
    const sy = (cells.height - 2 * margin) / (hi[1] - lo[1] || 1);
    const s = Math.min(sx, sy);
    const ox = (cells.width - s * (hi[0] - lo[0])) / 2;
    const oy = (cells.height - s * (hi[1] - lo[1])) / 2;
    return { g, s, x: (x) => ox + (x - lo[0]) * s, y: (y) => cells.height - oy - (y - lo[1]) * s };
  }

  function drawPlan(data) {
    const f = frame();
    const cells = $("plan-cells").getContext("2d");
    cells.clearRect(0, 0, $("plan-cells").width, $("plan-cells").height);
    const [cw, ch] = f.g.cell;
    f.g.points.forEach((p, i) => {
      const c = data.colours.subarray(3 * i, 3 * i + 3);
      cells.fillStyle = `rgb(${c[0]},${c[1]},${c[2]})`;
      // Whole pixels, so that a cell's centre shows its colour unblended.
      const x0 = Math.round(f.x(p[0] - cw / 2)), x1 = Math.round(f.x(p[0] + cw / 2));
      const y0 = Math.round(f.y(p[1] + ch / 2)), y1 = Math.round(f.y(p[1] - ch / 2));
      cells.fillRect(x0, y0, x1 - x0, y1 - y0);
    });

    const o = $("plan-overlay").getContext("2d");
    o.clearRect(0, 0, $("plan-overlay").width, $("plan-overlay").height);
    const [lo, hi] = info.extent;
    o.strokeStyle = "#444";
    o.lineWidth = 1.5;
    o.strokeRect(f.x(lo[0]), f.y(hi[1]), (hi[0] - lo[0]) * f.s, (hi[1] - lo[1]) * f.s);
    o.font = "11px system-ui, sans-serif";
    for (const iso of data.isolux) {
      o.strokeStyle = "rgba(255,255,255,0.85)";
      o.lineWidth = 1.2;
      for (const line of iso.polylines) {
        o.beginPath();
        line.forEach(([x, y], j) => (j ? o.lineTo(f.x(x), f.y(y)) : o.moveTo(f.x(x), f.y(y))));
        o.stroke();
        const [mx, my] = line[Math.floor(line.length / 2)];
        o.fillStyle = "white";
        o.fillText(String(iso.level), f.x(mx) + 2, f.y(my) - 2);
      }
    }
    o.fillStyle = "#e8e8e8";
    o.strokeStyle = "#333";
    info.channels.forEach((ch) => {
      for (const p of ch.emitters) {
        o.fillRect(f.x(p[0]) - 3, f.y(p[1]) - 3, 6, 6);
        o.strokeRect(f.x(p[0]) - 3, f.y(p[1]) - 3, 6, 6);
      }
    });
    info.channels.forEach((ch) => {
      const at = ch.brightest_point[zone];
      if (ch.emitters.length || at === null || at === undefined) return;
      const p = f.g.points[at];
      const [x, y] = [f.x(p[0]), f.y(p[1])];
      o.strokeStyle = "#d62828";
      o.lineWidth = 2;
      o.beginPath();
      o.moveTo(x - 6, y - 6); o.lineTo(x + 6, y + 6); o.moveTo(x + 6, y - 6); o.lineTo(x - 6, y + 6);
      o.stroke();
      o.fillStyle = "#d62828";
      o.fillText(ch.name, x + 8, y + 4);
    });
    for (const s of info.sensors) {
      const [x, y] = [f.x(s.position[0]), f.y(s.position[1])];
      o.fillStyle = "#f77f00";
      o.beginPath(); o.arc(x, y, 5, 0, 2 * Math.PI); o.fill();
      o.strokeStyle = "#222"; o.lineWidth = 1; o.stroke();
      o.fillStyle = "#111";
      o.fillText(s.name, x + 7, y - 6);
    }
    if (sky && info.daylight) {
      // The sun's bearing, turned into the room's axes (+y is `north` degrees from true north).
      const a = ((sky.azimuth - info.daylight.north) * Math.PI) / 180;
      const [cx, cy] = [$("plan-overlay").width - 30, 30];
      o.strokeStyle = "#f4a261"; o.fillStyle = "#f4a261"; o.lineWidth = 2;
      o.beginPath(); o.moveTo(cx, cy); o.lineTo(cx + 18 * Math.sin(a), cy - 18 * Math.cos(a)); o.stroke();
      o.beginPath(); o.arc(cx + 18 * Math.sin(a), cy - 18 * Math.cos(a), 5, 0, 2 * Math.PI); o.fill();
      o.fillStyle = "#333"; o.fillText(`sun ${sky.altitude.toFixed(0)}°`, cx - 40, cy + 26);
    }
  }

  // The map's colours, darkest first, one per bin: asked of the module once.
  let barColours = null;
  function drawBar(scale) {
    if (!barColours) {
      const n = check(wasm.bin_colours());
      barColours = Uint8Array.from(colours(n));
    }
    const canvas = $("colour-bar");
    const bar = canvas.getContext("2d");
    bar.clearRect(0, 0, canvas.width, canvas.height);
    const [x0, x1, y0, h] = [28, canvas.width - 36, 4, 18];
    const bins = barColours.length / 3;
    for (let k = 0; k < bins; k++) {
      bar.fillStyle = `rgb(${barColours[3 * k]},${barColours[3 * k + 1]},${barColours[3 * k + 2]})`;
      bar.fillRect(x0 + ((x1 - x0) * k) / bins, y0, (x1 - x0) / bins + 1, h);
    }
    bar.fillStyle = "#222";
    bar.font = "11px system-ui, sans-serif";
    const n = Math.round((scale.max - scale.min) / scale.step);
    for (let i = 0; i <= n; i++) {
      const v = scale.min + i * scale.step;
      const x = x0 + ((x1 - x0) * i) / n;
      bar.fillRect(x, y0 + h, 1, 4);
      const label = Number(v.toPrecision(6)).toString();
      bar.fillText(label, x - 3 * label.length, y0 + h + 16);
    }
    bar.fillText("lux", x1 + 6, y0 + 13);
  }

  // ---- one update ----------------------------------------------------------------------
  let last = null;
  function refresh(exceptSlider) {
    const list = readings();
    showReadings(list);
    showLevels(levels(), exceptSlider);
    const data = planData();
    if (data) {
      drawPlan(data);
      drawBar(data.scale);
      const [avg, min, max, uo] = data.figures;
      for (const [id, v, d] of [["e-avg", avg, 1], ["e-min", min, 1], ["e-max", max, 1], ["u-o", uo, 2]]) {
        $(id).textContent = id === "u-o" ? fmt(v, d) : `${fmt(v, d)} lx`;
        $(id).dataset.value = String(v);
      }
      $("summary").textContent = `scale ${data.scale.min}–${data.scale.max} lux, isolux every ${data.scale.step} lux`;
    }
    last = { readings: list, plan: data };
    updates += 1;
    document.body.dataset.updates = String(updates);
  }

  // ---- the target ----------------------------------------------------------------------
  function solve() {
    const controlled = info.channels.map((_, c) => c).filter((c) => $(`controlled-${c}`).checked);
    const weights = controlled.map((c) => Number($(`watts-${c}`).value));
    const bounds = [[1, Number($("target-zone").value), Number($("target-zone-lux").value), Infinity]];
    const s = Number($("target-sensor").value);
    if (s >= 0) bounds.push([0, s, Number($("target-sensor-lux").value), Infinity]);
    const input = [...controlled, ...weights, ...bounds.flat()];
    const ptr = wasm.input_numbers(input.length);
    new Float64Array(wasm.memory.buffer, ptr, input.length).set(input);
    const status = wasm.solve(controlled.length, bounds.length);
    const out = $("solution");
    if (status < 0) {
      out.textContent = text();
      out.className = "unmet";
      return;
    }
    const [power, met] = values(2);
    const why = text();
    out.className = met ? "" : "unmet";
    out.dataset.power = String(power);
    out.textContent = met
      ? `Met with ${power.toFixed(1)} W (least power for the channels ticked).`
      : `Not met: ${why}; levels set to the least violation, ${power.toFixed(1)} W.`;
    refresh();
  }

  // ---- export --------------------------------------------------------------------------
  function snapshot() {
    return { basis: fileName, sky, levels: levels(), readings: readings(),
      figures: last && last.plan ? { zone: info.zones[zone].name, average: last.plan.figures[0],
        minimum: last.plan.figures[1], maximum: last.plan.figures[2], uniformity: last.plan.figures[3] } : null };
  }

  function csv() {
    const s = snapshot();
    const rows = ["kind,name,level,arc,total_lux,electric_lux,daylight_lux"];
    for (const l of s.levels) rows.push(`channel,${l.channel},${l.level},${l.arc ?? ""},,,`);
    for (const r of s.readings) rows.push(`${r.kind},${r.name},,,${r.total},${r.electric},${r.daylight}`);
    if (s.figures) {
      const f = s.figures;
      rows.push(`grid,${f.zone} E_avg,,,${f.average},,`, `grid,${f.zone} E_min,,,${f.minimum},,`,
        `grid,${f.zone} E_max,,,${f.maximum},,`, `grid,${f.zone} U_o,,,${f.uniformity},,`);
    }
    return rows.join("\n") + "\n";
  }

  function download(name, type, body) {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([body], { type }));
    a.download = name;
    a.click();
    URL.revokeObjectURL(a.href);
  }

  // ---- timing --------------------------------------------------------------------------
  // `n` slider moves of channel `c`, each a full update (readings, levels, plan, colour bar):
  // the median and mean time per update, ms, by performance.now().
  function timeUpdates(n, c = 0) {
    const times = [];
    const start = performance.now();
    for (let i = 0; i < n; i++) {
      const t0 = performance.now();
      setLevel(c, (i % 100) / 100);
      times.push(performance.now() - t0);
    }
    const total = performance.now() - start;
    times.sort((a, b) => a - b);
    return { updates: n, median_ms: times[Math.floor(n / 2)], mean_ms: total / n };
  }

  // The canvas pixel at the centre of each cell of the plan, in the grid's order.
  function cellPixels() {
    const f = frame();
    return f.g.points.map((p) => [f.x(p[0]), f.y(p[1])]);
  }

  // ---- wiring --------------------------------------------------------------------------
  function wire() {
    $("basis-file").addEventListener("change", (e) => e.target.files[0] && openFile(e.target.files[0]));
    document.body.addEventListener("dragover", (e) => { e.preventDefault(); document.body.classList.add("dragging"); });
    document.body.addEventListener("dragleave", () => document.body.classList.remove("dragging"));
    document.body.addEventListener("drop", (e) => {
      e.preventDefault();
      document.body.classList.remove("dragging");
      if (e.dataTransfer.files[0]) openFile(e.dataTransfer.files[0]);
    });
    $("zone").addEventListener("change", () => { zone = Number($("zone").value); refresh(); });
    $("sky-model").addEventListener("change", () => { skyFields(); setSky(); });
    for (const id of ["sky-date", "sky-time", "sky-type", "sky-dhi", "sky-dni", "sky-water"]) {
      $(id).addEventListener("input", setSky);
    }
    $("solve").addEventListener("click", solve);
    $("export-csv").addEventListener("click", () => download("levels-readings.csv", "text/csv", csv()));
    $("export-json").addEventListener("click", () =>
      download("levels-readings.json", "application/json", JSON.stringify(snapshot(), null, 2)));
  }

  wire();
  load().catch((e) => setStatus(`The runtime did not load: ${e}`, true));
  return { open, snapshot, csv, timeUpdates, cellPixels, ready: () => wasm !== null };
})();
window.eigenradPage = page;
