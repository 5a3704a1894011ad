// shiproute bridge display: live feed (SSE), panels, time slider, forecast fetches.
"use strict";

(() => {
  const $ = (id) => document.getElementById(id);
  const view = new Chart.View($("chart-wrap"), $("chart-canvas"), $("chart-svg"));
  const S = { plan: null, history: [], ship: null, track: [], forecast: { cycles: [] }, stats: null,
              nowBase: null, nowAt: 0, follow: true, sliderT: null, lastSeq: 0, missed: 0,
              coastBox: null, sliceCache: new Map(), sliceKey: null, plansShown: 0, member: "p90" };
  window.__display = { plansShown: 0, lastPlanId: null, lastPlanShownAt: 0, coastDrawn: false, drawn: () => view.drawn };

  // ---------- formatting (UTC, kn, NM, deg true) ----------
  const pad = (n) => String(n).padStart(2, "0");
  function utc(t, withDate = true) {
    if (t === null || t === undefined || !isFinite(t)) return "--";
    const d = new Date(t * 1000);
    const hm = `${pad(d.getUTCHours())}:${pad(d.getUTCMinutes())}`;
    return withDate ? `${d.getUTCFullYear()}-${pad(d.getUTCMonth() + 1)}-${pad(d.getUTCDate())} ${hm}` : hm;
  }
  function short(t) {  // MM-DD HH:MM
    if (t === null || t === undefined || !isFinite(t)) return "--";
    const d = new Date(t * 1000);
    return `${pad(d.getUTCMonth() + 1)}-${pad(d.getUTCDate())} ${pad(d.getUTCHours())}:${pad(d.getUTCMinutes())}`;
  }
  function zoneTime(t, zone, long = true) {
    if (t === null || !isFinite(t)) return "--";
    const z = `${zone >= 0 ? "+" : ""}${zone}`;
    return long ? `${short(t + zone * 3600)} (UTC${z})` : `${short(t + zone * 3600)} ${z}`;
  }
  const fx = (v, n, unit = "") => (v === null || v === undefined || !isFinite(v)) ? "--" : v.toFixed(n) + unit;
  const sgn = (v, n, unit = "") => (v === null || v === undefined || !isFinite(v)) ? "--" : (v > 0 ? "+" : "") + v.toFixed(n) + unit;
  const hdg = (h) => (h === null || h === undefined || !isFinite(h)) ? "--" : String(((Math.round(h) % 360) + 360) % 360).padStart(3, "0");
  function dur(s) {
    if (!isFinite(s)) return "--";
    const neg = s < 0; s = Math.abs(s);
    const d = Math.floor(s / 86400), h = Math.floor((s % 86400) / 3600), m = Math.floor((s % 3600) / 60);
    return (neg ? "-" : "") + (d ? `${d} d ` : "") + `${h} h ${pad(m)} min`;
  }
  function zoneOf(lon) { return Math.max(-12, Math.min(12, Math.round(Chart.wrap(lon) / 15))); }
  function now() { return S.nowBase === null ? Date.now() / 1000 : S.nowBase + (performance.now() - S.nowAt) / 1000; }

  // ---------- geometry on the page (same great-circle interpolation as the node) ----------
  function slerp(a1, o1, a2, o2, f) {
    const r = Math.PI / 180, v = (a, o) => [Math.cos(a * r) * Math.cos(o * r), Math.cos(a * r) * Math.sin(o * r), Math.sin(a * r)];
    const A = v(a1, o1), B = v(a2, o2), dot = Math.max(-1, Math.min(1, A[0] * B[0] + A[1] * B[1] + A[2] * B[2]));
    const w = Math.acos(dot); if (w < 1e-12) return [a1, o1];
    const s = Math.sin(w), ka = Math.sin((1 - f) * w) / s, kb = Math.sin(f * w) / s;
    const P = [0, 1, 2].map((i) => ka * A[i] + kb * B[i]);
    return [Math.atan2(P[2], Math.hypot(P[0], P[1])) / r, Math.atan2(P[1], P[0]) / r];
  }
  function planPositionAt(p, t) {
    const ts = p.time_s, n = ts.length;
    if (t <= ts[0]) return [p.lat[0], p.lon[0]];
    for (let i = 0; i < n - 1; i++) {
      if (t <= ts[i + 1]) { const span = ts[i + 1] - ts[i]; return slerp(p.lat[i], p.lon[i], p.lat[i + 1], p.lon[i + 1], span > 0 ? (t - ts[i]) / span : 1); }
    }
    return [p.lat[n - 1], p.lon[n - 1]];
  }

  // ---------- plan header, schedule, history ----------
  function showPlan(ev) {
    const p = ev.plan;
    S.plan = p; S.history = ev.history || [];
    view.data.plan = p; view.data.previous = ev.previous; view.data.gc = ev.great_circle;
    $("chart-empty").classList.toggle("hidden", !!p);
    if (ev.chart_box) { view.setBox(ev.chart_box, false); ensureCoast(ev.chart_box); }
    if (!p) { view.requestRender(); return; }
    $("plan-ident").textContent = `plan ${p.plan_id} · cycle ${p.cycle_id} · ${p.method} · ${p.ship_name} · ${p.trigger_kind}`;
    $("fuel").textContent = fx(p.total_fuel_t, 1, " t");
    const sv = $("saved");
    sv.textContent = p.fuel_saved_t === null ? "no baseline" : p.fuel_saved_t >= 0
      ? `${fx(p.fuel_saved_t, 1, " t")} (${fx(p.fuel_saved_pct, 1, " %")}) less`
      : `${fx(-p.fuel_saved_t, 1, " t")} (${fx(-p.fuel_saved_pct, 1, " %")}) more`;
    sv.className = "big " + (p.fuel_saved_t !== null && p.fuel_saved_t < 0 ? "warn" : "");
    $("eta").textContent = utc(p.eta_s) + " UTC"; $("eta").dataset.etaS = p.eta_s;
    $("eta-rta").textContent = p.eta_minus_rta_h === null ? "--" : `${sgn(p.eta_minus_rta_h, 1, " h")} ${p.eta_minus_rta_h > 0 ? "late" : "early"}`;
    $("eta-rta").className = "big " + (p.eta_minus_rta_h > 0.05 ? "late" : "");
    $("rta").textContent = utc(p.rta_s) + " UTC";
    $("distance").textContent = fx(p.total_distance_nm, 0, " NM");
    $("wp-count").textContent = String(p.waypoint_count);
    $("compute").textContent = fx(p.compute_time_s, 2, " s");
    const fe = $("feasible");
    fe.className = "feasible " + (p.feasible ? "yes" : "no");
    fe.textContent = p.feasible ? "FEASIBLE: all constraints met" : "NOT FEASIBLE: " + p.infeasible_reasons.join("; ");
    const ul = $("warnings"); ul.replaceChildren();
    for (const w of p.warnings) { const li = document.createElement("li"); li.textContent = w; ul.appendChild(li); }
    if (!p.warnings.length) { const li = document.createElement("li"); li.className = "none"; li.textContent = "no warnings"; ul.appendChild(li); }
    showEnsemble(p.ensemble);
    buildSchedule(p); buildHistory(); setupSlider(true); updateLegLegend();
    S.plansShown += 1;
    Object.assign(window.__display, { plansShown: S.plansShown, lastPlanId: p.plan_id, lastPlanShownAt: Date.now() });
  }
  function showEnsemble(e) {  // the plan's spread over forecast members (null: one forecast)
    $("ensemble-panel").classList.toggle("hidden", !e);
    if (!e) return;
    $("ens-ident").textContent = `${e.members} members · optimised for ${e.risk_measure}`;
    const cells = (id, vals, f) => [...$(id).querySelectorAll("td")].forEach((td, i) => { td.textContent = f(vals[i]); });
    cells("ens-fuel", e.fuel_quantiles_t, (v) => fx(v, 1));
    cells("ens-eta", e.eta_quantiles_s, (v) => short(v));
    const pct = (v) => (v === null || v === undefined || !isFinite(v)) ? "--" : `${(100 * v).toFixed(0)} %`;
    $("ens-p-hs").textContent = pct(e.p_hs_violation); $("ens-p-late").textContent = pct(e.p_late);
  }
  function buildSchedule(p) {
    const tb = $("schedule").querySelector("tbody"); tb.replaceChildren();
    p.schedule.forEach((r) => {
      const tr = document.createElement("tr"); tr.dataset.start = r.start_s; tr.dataset.rpm = r.rpm;
      const cells = [r.stage, short(r.start_s), zoneTime(r.start_s, r.zone_h, false), fx(r.rpm, 1), hdg(r.heading_deg),
        fx(r.sog_kn, 1), fx(r.fuel_t, 1), fx(r.hs_m, 1),
        r.hs_min_m === null || r.hs_min_m === undefined ? "--" : `${fx(r.hs_min_m, 1)}–${fx(r.hs_max_m, 1)}`];
      cells.forEach((c, i) => { const td = document.createElement("td"); td.textContent = c; if (i === 7 && r.flags) td.className = "flag"; tr.appendChild(td); });
      tb.appendChild(tr);
    });
    tickSchedule();
  }
  function tickSchedule() {
    const p = S.plan; if (!p) return;
    const t = now(), rows = [...$("schedule").querySelectorAll("tbody tr")];
    let cur = -1;
    rows.forEach((tr, i) => { if (t >= +tr.dataset.start) cur = i; });
    if (t > p.eta_s) cur = -1;
    rows.forEach((tr, i) => { tr.classList.toggle("current", i === cur); tr.classList.toggle("past", cur >= 0 && i < cur); });
    const cd = $("countdown");
    if (t < p.time_s[0]) { cd.innerHTML = ""; cd.append("Departure in ", bold(dur(p.time_s[0] - t)), ` at ${fx(p.schedule[0]?.rpm, 1)} rpm`); }
    else if (cur < 0) { cd.textContent = t > p.eta_s ? "Arrived (plan complete)" : "--"; }
    else {
      const rpm = p.schedule[cur].rpm; let nxt = null;
      for (let k = cur + 1; k < p.schedule.length; k++) if (Math.abs(p.schedule[k].rpm - rpm) >= 0.5) { nxt = p.schedule[k]; break; }
      cd.replaceChildren();
      cd.append(`Stage ${cur + 1}: hold `, bold(`${fx(rpm, 1)} rpm`), `, ${hdg(p.schedule[cur].heading_deg)}°T. `);
      if (nxt) cd.append("Next RPM change ", bold(`${fx(rpm, 1)} → ${fx(nxt.rpm, 1)}`), ` at ${short(nxt.start_s)} UTC, in `, bold(dur(nxt.start_s - t)));
      else cd.append("No RPM change before arrival.");
    }
    const ship = S.ship, zone = ship ? zoneOf(ship.lon_deg) : null;
    $("clock-utc").textContent = utc(t) + " UTC";
    $("clock-zone").textContent = zone === null ? "--" : zoneTime(t, zone);
  }
  function bold(text) { const b = document.createElement("b"); b.textContent = text; return b; }
  function buildHistory() {
    const tb = $("history").querySelector("tbody"); tb.replaceChildren();
    [...S.history].reverse().forEach((h) => {
      const tr = document.createElement("tr");
      const cells = [short(h.stamp_s), h.plan_id, h.trigger_kind, h.cycle_id, sgn(h.d_eta_h, 2), sgn(h.d_fuel_t, 1), fx(h.total_fuel_t, 1), h.feasible ? "ok" : "FLAG"];
      cells.forEach((c, i) => { const td = document.createElement("td"); td.textContent = c; if (i === 2) { td.className = "trig"; td.title = h.trigger; } if (i === 3) { td.className = "cyc"; td.title = h.cycle_id; } if (i === 7 && !h.feasible) td.className = "flag"; tr.appendChild(td); });
      tb.appendChild(tr);
    });
  }
  function updateLegLegend() {
    Chart.drawRamp($("leg-ramp"), Chart.rampColour);
    const p = S.plan; let r = null;
    if (p) {
      const vals = (view.data.legMode === "fuel" ? p.leg_fuel_t_per_day : p.leg_rpm).filter((v) => v !== null && isFinite(v));
      if (vals.length) r = [Math.min(...vals), Math.max(...vals)];
    }
    $("leg-min").textContent = r ? fx(r[0], 1) : "--"; $("leg-max").textContent = r ? fx(r[1], 1) : "--";
  }

  // ---------- ship ----------
  function showShip(fix, trackAdd, replaceTrack) {
    if (!fix) return;
    S.ship = fix; S.nowBase = fix.time_s; S.nowAt = performance.now();
    if (replaceTrack) S.track = replaceTrack.slice(); else if (trackAdd) S.track.push(...trackAdd);
    view.data.ship = fix; view.data.track = S.track;
  }

  // ---------- time slider and forecast ----------
  function timeRange() {
    const p = S.plan; if (!p) return null;
    return [Math.min(p.time_s[0], now()), p.eta_s];
  }
  function setupSlider(live) {
    const r = timeRange(); if (!r) return;
    const sl = $("time-slider");
    sl.min = Math.floor(r[0] / 3600); sl.max = Math.ceil(r[1] / 3600);
    if (S.follow || S.sliderT === null) S.sliderT = Math.max(r[0], Math.min(r[1], now()));
    sl.value = Math.round(S.sliderT / 3600);
    applyTime(live);
  }
  function applyTime(live) {
    const t = S.sliderT; if (t === null || !S.plan) return;
    view.data.planMark = planPositionAt(S.plan, t);
    const c = pickCycle(), lbl = $("time-label");
    let txt = `${utc(t)} UTC (${sgn((t - now()) / 3600, 1, " h")} from now)`;
    if (c && c.times_s.length) {
      let best = 0; c.times_s.forEach((v, i) => { if (Math.abs(v - t) < Math.abs(c.times_s[best] - t)) best = i; });
      const step = c.times_s.length > 1 ? c.times_s[1] - c.times_s[0] : 0;
      if (t < c.times_s[0] - step || t > c.times_s[c.times_s.length - 1] + step) { txt += " · no forecast for this time"; view.data.slice = null; }
      else {
        txt += ` · forecast valid ${utc(c.times_s[best], false)} UTC`;
        if (c.members > 1) txt += ` · ${memberName(c, S.member)}`;
        loadSlice(c.cycle_id, c.indices[best], c.members > 1 ? S.member : "0");
      }
    } else txt += " · no forecast received";
    lbl.textContent = txt;
    if (live) view.requestRender(); else view.render();
  }
  function pickCycle() {
    const cs = S.forecast.cycles.filter((c) => c.received > 0);
    return cs.find((c) => S.plan && c.cycle_id === S.plan.cycle_id) || cs[cs.length - 1] || null;
  }
  function memberName(c, m) {
    if (m === "p90") return `P90 of ${c.members} members`;
    const lbl = c.member_labels[+m];
    return `member ${m}` + (lbl && lbl !== String(m) ? ` (${lbl})` : "");
  }
  function showMembers(c) {  // the member selector and the members' Hs-peak tracks
    const row = $("member-row"), sel = $("member-view"), n = c ? c.members : 1;
    row.classList.toggle("hidden", n < 2);
    view.data.tracks = n > 1 && $("show-tracks").checked ? c.tracks : null;
    if (n < 2) return;
    if (sel.dataset.cycle !== c.cycle_id) {
      sel.replaceChildren();
      for (const v of ["p90", ...Array.from({ length: n }, (_, m) => String(m))]) {
        const o = document.createElement("option"); o.value = v; o.textContent = memberName(c, v); sel.appendChild(o);
      }
      sel.dataset.cycle = c.cycle_id;
      if (S.member !== "p90" && +S.member >= n) S.member = "p90";
      sel.value = S.member;
    }
  }
  async function loadSlice(cycle, index, member = "0") {
    const key = `${cycle}#${index}#${member}`;
    if (S.sliceKey === key && view.data.slice) return;
    S.sliceKey = key;
    let s = S.sliceCache.get(key);
    if (!s) {
      try {
        const r = await fetch(`/api/forecast?cycle=${encodeURIComponent(cycle)}&index=${index}&member=${member}`);
        if (!r.ok) return;
        const j = await r.json(), bin = atob(j.hs_b64), hs = new Uint8Array(bin.length);
        for (let i = 0; i < bin.length; i++) hs[i] = bin.charCodeAt(i);
        s = { grid: j.grid, hs, step: j.hs_step_m, missing: j.hs_missing, wind: j.wind, valid_s: j.valid_s };
        if (S.sliceCache.size > 160) S.sliceCache.delete(S.sliceCache.keys().next().value);
        S.sliceCache.set(key, s);
      } catch (e) { return; }
    }
    if (S.sliceKey === key) { view.data.slice = s; view.requestRender(); }
  }
  $("time-slider").addEventListener("input", (e) => { S.follow = false; S.sliderT = +e.target.value * 3600; $("now-btn").classList.remove("on"); applyTime(); });
  $("now-btn").addEventListener("click", () => { S.follow = true; setupSlider(); });

  // ---------- coastline ----------
  async function ensureCoast(box) {
    const b = S.coastBox;
    if (b && b[0] <= box[0] && b[1] >= box[1] && b[2] <= box[2] && b[3] >= box[3]) return;
    S.coastBox = box;
    try {
      const r = await fetch("/api/coast"); if (!r.ok) return;
      const j = await r.json();
      S.coastBox = j.box; view.data.coast = j; $("st-credit").textContent = `${j.credit} · units: kn, NM, ° true, UTC`;
      view.render(); window.__display.coastDrawn = true;
    } catch (e) { S.coastBox = null; }
  }

  // ---------- status ----------
  function showStats(st) {
    if (!st) return; S.stats = st;
    const r = st.received || {}, short = (k) => k.split("/").pop();
    $("st-msgs").textContent = "received " + (Object.keys(r).map((k) => `${short(k)} ${r[k]}`).join(", ") || "nothing yet");
    const m = $("st-malformed");
    m.textContent = `malformed ${st.malformed_total}` + (st.malformed_total ? ` (last: ${st.last_problem})` : "");
    m.className = st.malformed_total ? "bad" : "ok"; m.title = st.last_problem || "";
    $("st-missed").textContent = `missed ${S.missed}` + (st.feed ? ` · pages ${st.feed.clients}` : "");
    if (st.now_s && !S.ship) { S.nowBase = st.now_s; S.nowAt = performance.now(); }
  }
  function showForecast(f) {
    S.forecast = f || { cycles: [] };
    const c = pickCycle();
    $("st-forecast").textContent = c ? `forecast ${c.cycle_id}: ${c.received}/${c.slice_count} slices`
      + (c.members > 1 ? ` · ${c.members} members × ${c.times_per_member} times` : "") : "forecast: none";
    showMembers(c);
    applyTime(true);
  }

  // ---------- live feed ----------
  function onEvent(name, fn) {
    return (e) => {
      // a gap in the shared sequence = updates this page did not get (a resync snapshot
      // carries the last sequence number and replaces what was skipped)
      const seq = +e.lastEventId;
      if (S.lastSeq && seq > S.lastSeq + 1 && name !== "snapshot") S.missed += seq - S.lastSeq - 1;
      else if (S.lastSeq && seq > S.lastSeq && name === "snapshot") S.missed += seq - S.lastSeq;
      S.lastSeq = seq;
      try { fn(JSON.parse(e.data)); } catch (err) { console.error(name, err); }
    };
  }
  function connect() {
    const es = new EventSource("/events");
    const link = $("link");
    link.textContent = "CONNECTING"; link.className = "link wait";
    es.onopen = () => { link.textContent = "LIVE"; link.className = "link on"; };
    es.onerror = () => { link.textContent = es.readyState === 2 ? "OFFLINE" : "RECONNECTING"; link.className = "link " + (es.readyState === 2 ? "off" : "wait"); if (es.readyState === 2) setTimeout(connect, 2000); };
    es.addEventListener("snapshot", onEvent("snapshot", (s) => {
      showShip(s.ship, null, s.track || []); showStats(s.stats); S.forecast = s.forecast || { cycles: [] };
      if (s.chart_box) ensureCoast(s.chart_box);
      if (s.plan) showPlan(s); else view.requestRender();
      showForecast(s.forecast);
    }));
    es.addEventListener("plan", onEvent("plan", showPlan));
    es.addEventListener("ship", onEvent("ship", (e) => { showShip(e.fix, e.track_add); showStats(e.stats); if (S.follow) setupSlider(true); else view.requestRender(); tickSchedule(); }));
    es.addEventListener("forecast", onEvent("forecast", showForecast));
    es.addEventListener("stats", onEvent("stats", showStats));
  }

  // ---------- controls ----------
  const theme = localStorage.getItem("shiproute-theme") || "night";
  function setTheme(t) { document.documentElement.dataset.theme = t; $("theme-btn").textContent = t === "night" ? "Day" : "Night"; localStorage.setItem("shiproute-theme", t); view.render(); }
  $("theme-btn").addEventListener("click", () => setTheme(document.documentElement.dataset.theme === "night" ? "day" : "night"));
  $("leg-colour").addEventListener("change", (e) => { view.data.legMode = e.target.value; view.render(); updateLegLegend(); });
  $("show-hs").addEventListener("change", (e) => { view.data.showHs = e.target.checked; view.render(); });
  $("show-wind").addEventListener("change", (e) => { view.data.showWind = e.target.checked; view.render(); });
  $("member-view").addEventListener("change", (e) => { S.member = e.target.value; applyTime(); });
  $("show-tracks").addEventListener("change", () => { showMembers(pickCycle()); view.render(); });
  Chart.drawRamp($("hs-ramp"), (f) => { const c = Chart.hsColour(f * 14); return `rgb(${c.join(",")})`; });
  setTheme(theme);
  view.resize();
  setInterval(tickSchedule, 1000);
  connect();
})();
