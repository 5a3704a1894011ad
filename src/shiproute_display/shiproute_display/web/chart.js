// shiproute bridge display: the chart (Mercator on a continuous longitude, canvas + SVG).
// Canvas: sea, Hs field, land, graticule, wind barbs. SVG overlay: routes and markers.
"use strict";

const Chart = (() => {
  const D2R = Math.PI / 180;
  const RAMP = ["#440154", "#3b528b", "#21918c", "#5ec962", "#fde725"];  // legs (viridis stops)
  const HS_STOPS = [[0, [28, 58, 110]], [2, [36, 112, 170]], [4, [52, 160, 120]],
    [6, [215, 195, 60]], [8, [230, 120, 40]], [10, [200, 40, 40]], [14, [150, 30, 150]]];
  const SVGNS = "http://www.w3.org/2000/svg";

  function wrap(lon) { return ((lon + 180) % 360 + 360) % 360 - 180; }
  function css(name) { return getComputedStyle(document.documentElement).getPropertyValue(name).trim(); }
  function hex(c) { const n = parseInt(c.slice(1), 16); return [(n >> 16) & 255, (n >> 8) & 255, n & 255]; }
  function rampColour(f) {
    f = Math.max(0, Math.min(1, isFinite(f) ? f : 0));
    const x = f * (RAMP.length - 1), i = Math.min(RAMP.length - 2, Math.floor(x)), t = x - i;
    const a = hex(RAMP[i]), b = hex(RAMP[i + 1]);
    return `rgb(${a.map((v, k) => Math.round(v + t * (b[k] - v))).join(",")})`;
  }
  function hsColour(h) {
    for (let i = 0; i < HS_STOPS.length - 1; i++) {
      const [h0, c0] = HS_STOPS[i], [h1, c1] = HS_STOPS[i + 1];
      if (h <= h1) { const t = Math.max(0, (h - h0) / (h1 - h0)); return c0.map((v, k) => Math.round(v + t * (c1[k] - v))); }
    }
    return HS_STOPS[HS_STOPS.length - 1][1];
  }

  class View {
    constructor(wrapEl, canvas, svg) {
      this.wrap = wrapEl; this.canvas = canvas; this.svg = svg;
      this.lon0 = 180; this.scale = 4; this.tx = 0; this.ty = 0; this.w = 1; this.h = 1;
      this.data = { coast: null, plan: null, previous: null, gc: null, track: [], ship: null,
                    planMark: null, slice: null, legMode: "rpm", showHs: true, showWind: true };
      this.userMoved = false; this.drawn = 0;
      this._bindPanZoom();
      new ResizeObserver(() => this.resize()).observe(wrapEl);
    }
    // --- projection ---
    lonC(lon) { return this.lon0 + wrap(lon - this.lon0); }
    px(lat, lon) {
      const x = (this.lonC(lon) - this.lon0) * this.scale;
      const la = Math.max(-85, Math.min(85, lat)) * D2R;
      const y = -Math.log(Math.tan(Math.PI / 4 + la / 2)) / D2R * this.scale;
      return [x + this.tx, y + this.ty];
    }
    inv(x, y) {
      const lon = (x - this.tx) / this.scale + this.lon0;
      const lat = (2 * Math.atan(Math.exp(-((y - this.ty) / this.scale) * D2R)) - Math.PI / 2) / D2R;
      return [lat, wrap(lon)];
    }
    fit(box) {  // box: [lonMin, lonMax, latMin, latMax] continuous longitudes
      const [l0, l1, a0, a1] = box;
      this.lon0 = (l0 + l1) / 2;
      const yOf = (lat) => -Math.log(Math.tan(Math.PI / 4 + Math.max(-85, Math.min(85, lat)) * D2R / 2)) / D2R;
      const spanX = Math.max(1, l1 - l0), spanY = Math.max(1, yOf(a0) - yOf(a1));
      this.scale = Math.min(this.w / spanX, this.h / spanY) * 0.96;
      this.tx = this.w / 2;
      this.ty = this.h / 2 - (yOf(a0) + yOf(a1)) / 2 * this.scale;
    }
    resize() {
      const r = this.wrap.getBoundingClientRect();
      const dpr = window.devicePixelRatio || 1;
      const changed = Math.abs(r.width - this.w) > 1 || Math.abs(r.height - this.h) > 1;
      this.w = Math.max(1, r.width); this.h = Math.max(1, r.height);
      this.canvas.width = Math.round(this.w * dpr); this.canvas.height = Math.round(this.h * dpr);
      this.svg.setAttribute("viewBox", `0 0 ${this.w} ${this.h}`);
      if (changed && this.box && !this.userMoved) this.fit(this.box);
      this.render();
    }
    setBox(box, force) {
      const same = this.box && box && this.box.every((v, i) => v === box[i]);
      this.box = box;
      if (force || (!same && !this.userMoved)) this.fit(box);
    }
    _bindPanZoom() {
      let drag = null;
      const c = this.canvas;
      c.addEventListener("mousedown", (e) => { drag = [e.clientX, e.clientY]; });
      window.addEventListener("mouseup", () => { drag = null; });
      c.addEventListener("mousemove", (e) => {
        const r = c.getBoundingClientRect();
        const [lat, lon] = this.inv(e.clientX - r.left, e.clientY - r.top);
        const el = document.getElementById("cursor-pos");
        if (el) el.textContent = fmtLatLon(lat, lon);
        if (!drag) return;
        this.tx += e.clientX - drag[0]; this.ty += e.clientY - drag[1];
        drag = [e.clientX, e.clientY]; this.userMoved = true; this.render();
      });
      c.addEventListener("wheel", (e) => {
        e.preventDefault();
        const r = c.getBoundingClientRect(), mx = e.clientX - r.left, my = e.clientY - r.top;
        const k = e.deltaY < 0 ? 1.25 : 0.8;
        this.tx = mx - (mx - this.tx) * k; this.ty = my - (my - this.ty) * k; this.scale *= k;
        this.userMoved = true; this.render();
      }, { passive: false });
      c.addEventListener("dblclick", () => { this.userMoved = false; if (this.box) this.fit(this.box); this.render(); });
    }
    // --- drawing ---
    requestRender() {  // coalesce bursts of live updates into one redraw per frame
      if (this._pending) return;
      this._pending = true;
      requestAnimationFrame(() => { this._pending = false; this.render(); });
    }
    render() {
      const ctx = this.canvas.getContext("2d");
      const dpr = window.devicePixelRatio || 1;
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = css("--sea"); ctx.fillRect(0, 0, this.w, this.h);
      if (this.data.showHs) this._drawHs(ctx);
      this._drawLand(ctx);
      this._drawGraticule(ctx);
      if (this.data.showWind) this._drawWind(ctx);
      this._drawSvg();
      this.drawn += 1;
    }
    _drawHs(ctx) {
      const s = this.data.slice; if (!s) return;
      const [lat0, dlat, nlat, lon0, dlon, nlon] = s.grid;
      ctx.globalAlpha = document.documentElement.dataset.theme === "night" ? 0.45 : 0.6;
      for (let i = 0; i < nlat; i++) {
        const la = lat0 + i * dlat;
        const [, y0] = this.px(la - dlat / 2, this.lon0), [, y1] = this.px(la + dlat / 2, this.lon0);
        for (let j = 0; j < nlon; j++) {
          const code = s.hs[i * nlon + j]; if (code === s.missing) continue;
          const lo = this.lonC(lon0 + j * dlon);
          const x0 = (lo - dlon / 2 - this.lon0) * this.scale + this.tx;
          const c = hsColour(code * s.step);
          ctx.fillStyle = `rgb(${c[0]},${c[1]},${c[2]})`;
          ctx.fillRect(x0, y1, dlon * this.scale + 0.7, y0 - y1 + 0.7);
        }
      }
      ctx.globalAlpha = 1;
    }
    _drawLand(ctx) {
      const coast = this.data.coast; if (!coast) return;
      ctx.fillStyle = css("--land"); ctx.strokeStyle = css("--coast"); ctx.lineWidth = 0.8;
      ctx.beginPath();
      for (const ring of coast.rings) {
        // rings come in continuous longitudes: shift each ring as a whole next to lon0
        const shift = 360 * Math.round((this.lon0 - ring[0]) / 360);
        for (let k = 0; k < ring.length; k += 2) {
          const x = (ring[k] + shift - this.lon0) * this.scale + this.tx;
          const la = ring[k + 1] * D2R;
          const y = -Math.log(Math.tan(Math.PI / 4 + la / 2)) / D2R * this.scale + this.ty;
          if (k === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
        }
        ctx.closePath();
      }
      ctx.fill(); ctx.stroke();
    }
    _drawGraticule(ctx) {
      const [latA] = this.inv(0, this.h), [latB] = this.inv(0, 0);
      const lonA = (0 - this.tx) / this.scale + this.lon0, lonB = (this.w - this.tx) / this.scale + this.lon0;
      const span = lonB - lonA, step = span > 120 ? 20 : span > 50 ? 10 : span > 20 ? 5 : span > 8 ? 2 : 1;
      ctx.strokeStyle = css("--grid"); ctx.fillStyle = css("--muted"); ctx.lineWidth = 1;
      ctx.font = "11px ui-monospace, monospace";
      for (let lo = Math.ceil(lonA / step) * step; lo <= lonB; lo += step) {
        const x = (lo - this.lon0) * this.scale + this.tx;
        ctx.beginPath(); ctx.moveTo(x, 0); ctx.lineTo(x, this.h); ctx.stroke();
        const w = wrap(lo); ctx.fillText(`${Math.abs(w)}°${w < 0 ? "W" : w > 0 && w < 180 ? "E" : ""}`, x + 3, 12);
      }
      for (let la = Math.ceil(latA / step) * step; la <= latB; la += step) {
        const [, y] = this.px(la, this.lon0);
        ctx.beginPath(); ctx.moveTo(0, y); ctx.lineTo(this.w, y); ctx.stroke();
        ctx.fillText(`${Math.abs(la)}°${la < 0 ? "S" : la > 0 ? "N" : ""}`, 3, y - 3);
      }
    }
    _drawWind(ctx) {
      const s = this.data.slice; if (!s || !s.wind) return;
      ctx.strokeStyle = css("--barb"); ctx.fillStyle = css("--barb"); ctx.lineWidth = 1.1;
      const minGap = 26; let lastY = -1e9; const placed = [];
      for (let k = 0; k < s.wind.length; k += 4) {
        const [x, y] = this.px(s.wind[k + 1], s.wind[k]);
        if (x < -20 || y < -20 || x > this.w + 20 || y > this.h + 20) continue;
        if (placed.some(([px, py]) => Math.abs(px - x) < minGap && Math.abs(py - y) < minGap)) continue;
        placed.push([x, y]); lastY = y;
        drawBarb(ctx, x, y, s.wind[k + 2], s.wind[k + 3]);
      }
      return lastY;
    }
    _line(parent, lats, lons, attrs) {
      if (!lats || lats.length < 2) return;
      let d = "", prevX = null;
      for (let i = 0; i < lats.length; i++) {
        const [x, y] = this.px(lats[i], lons[i]);
        d += (i === 0 || (prevX !== null && Math.abs(x - prevX) > this.w * 3) ? "M" : "L") + x.toFixed(1) + " " + y.toFixed(1);
        prevX = x;
      }
      const p = document.createElementNS(SVGNS, "path");
      p.setAttribute("d", d); p.setAttribute("fill", "none");
      for (const [k, v] of Object.entries(attrs)) p.setAttribute(k, v);
      parent.appendChild(p);
      return p;
    }
    _drawSvg() {
      const g = (id) => { const el = document.getElementById(id); el.replaceChildren(); return el; };
      const gc = g("layer-gc"), prev = g("layer-prev"), plan = g("layer-plan"), track = g("layer-track"), marks = g("layer-marks");
      const d = this.data, tracks = g("layer-tracks");
      (d.tracks || []).forEach((tr, m) => {  // each member's Hs-peak track: [lon, lat, t, hs]
        const el = this._line(tracks, tr.map((q) => q[1]), tr.map((q) => q[0]), { class: "member-track" });
        if (el) { const t = document.createElementNS(SVGNS, "title"); t.textContent = `member ${m}: highest Hs`; el.appendChild(t); }
      });
      if (d.gc) this._line(gc, d.gc.lat, d.gc.lon, { stroke: css("--gc"), "stroke-width": 1.6, "stroke-dasharray": "7 6", id: "great-circle" });
      if (d.previous) this._line(prev, d.previous.lat, d.previous.lon, { stroke: css("--prev"), "stroke-width": 2, "stroke-opacity": 0.55, id: "previous-plan" });
      if (d.plan) {
        const p = d.plan, vals = d.legMode === "fuel" ? p.leg_fuel_t_per_day : p.leg_rpm;
        const fin = vals.filter((v) => v !== null && isFinite(v));
        const lo = Math.min(...fin), hi = Math.max(...fin);
        for (let i = 0; i < p.lat.length - 1; i++) {
          const f = hi > lo ? (vals[i] - lo) / (hi - lo) : 0.5;
          const el = this._line(plan, [p.lat[i], p.lat[i + 1]], [p.lon[i], p.lon[i + 1]],
            { stroke: rampColour(f), "stroke-width": 4.5, "stroke-linecap": "round", class: "leg" });
          if (el) { const t = document.createElementNS(SVGNS, "title"); t.textContent = `stage ${i + 1}: ${vals[i]}`; el.appendChild(t); }
        }
        for (let i = 0; i < p.lat.length; i++) {
          const [x, y] = this.px(p.lat[i], p.lon[i]);
          const c = document.createElementNS(SVGNS, "circle");
          c.setAttribute("cx", x.toFixed(1)); c.setAttribute("cy", y.toFixed(1)); c.setAttribute("r", i === 0 || i === p.lat.length - 1 ? 4.5 : 2.4);
          c.setAttribute("fill", css("--panel")); c.setAttribute("stroke", css("--plan")); c.setAttribute("stroke-width", 1.5);
          c.setAttribute("class", "waypoint"); plan.appendChild(c);
        }
        this.legRange = [lo, hi];
      }
      if (d.track && d.track.length > 1) this._line(track, d.track.map((q) => q[0]), d.track.map((q) => q[1]), { stroke: css("--track"), "stroke-width": 2, id: "ship-track" });
      if (d.planMark) {
        const [x, y] = this.px(d.planMark[0], d.planMark[1]);
        const c = document.createElementNS(SVGNS, "circle");
        c.setAttribute("id", "plan-marker"); c.setAttribute("cx", x.toFixed(1)); c.setAttribute("cy", y.toFixed(1));
        c.setAttribute("r", 7); c.setAttribute("fill", "none"); c.setAttribute("stroke", css("--pmark")); c.setAttribute("stroke-width", 2.5);
        marks.appendChild(c);
      }
      if (d.ship) {
        const [x, y] = this.px(d.ship.lat_deg, d.ship.lon_deg);
        const hdg = d.ship.heading_deg ?? d.ship.cog_deg ?? 0;
        const s = document.createElementNS(SVGNS, "path");
        s.setAttribute("id", "ship-marker"); s.setAttribute("d", "M0 -11 L6 8 L0 4 L-6 8 Z");
        s.setAttribute("transform", `translate(${x.toFixed(1)} ${y.toFixed(1)}) rotate(${hdg})`);
        s.setAttribute("fill", css("--ship")); s.setAttribute("stroke", css("--panel")); s.setAttribute("stroke-width", 1);
        marks.appendChild(s);
      }
    }
  }

  function drawBarb(ctx, x, y, u, v) {
    // staff points to where the wind comes from; feathers: pennant 50 kn, full 10 kn, half 5 kn
    const kn = Math.hypot(u, v) * 1.943844;
    if (kn < 2.5) { ctx.beginPath(); ctx.arc(x, y, 3, 0, 2 * Math.PI); ctx.stroke(); return; }
    const len = 20, ang = Math.atan2(-v, -u);  // math angle of the "from" direction
    const dx = Math.cos(ang), dy = -Math.sin(ang);  // screen y down
    const nx = -dy, ny = dx;  // feather side
    const ex = x + dx * len, ey = y + dy * len;
    ctx.beginPath(); ctx.moveTo(x, y); ctx.lineTo(ex, ey); ctx.stroke();
    let rest = Math.round(kn / 5) * 5, pos = 0;
    const fx = (p) => ex - dx * p, fy = (p) => ey - dy * p;
    while (rest >= 50) {
      ctx.beginPath(); ctx.moveTo(fx(pos), fy(pos)); ctx.lineTo(fx(pos) + nx * 9, fy(pos) + ny * 9);
      ctx.lineTo(fx(pos + 5), fy(pos + 5)); ctx.closePath(); ctx.fill(); pos += 7; rest -= 50;
    }
    while (rest >= 10) {
      ctx.beginPath(); ctx.moveTo(fx(pos), fy(pos)); ctx.lineTo(fx(pos) + nx * 9 + dx * 3, fy(pos) + ny * 9 + dy * 3); ctx.stroke();
      pos += 4; rest -= 10;
    }
    if (rest >= 5) {
      if (pos === 0) pos = 4;
      ctx.beginPath(); ctx.moveTo(fx(pos), fy(pos)); ctx.lineTo(fx(pos) + nx * 5 + dx * 1.5, fy(pos) + ny * 5 + dy * 1.5); ctx.stroke();
    }
  }

  function fmtLatLon(lat, lon) {
    const f = (v, p, n) => { const a = Math.abs(v), d = Math.floor(a), m = (a - d) * 60;
      return `${String(d).padStart(n, "0")}°${m.toFixed(1).padStart(4, "0")}'${v < 0 ? p[1] : p[0]}`; };
    return `${f(lat, "NS", 2)} ${f(lon, "EW", 3)}`;
  }

  function drawRamp(canvas, fn) {
    const ctx = canvas.getContext("2d");
    for (let i = 0; i < canvas.width; i++) { ctx.fillStyle = fn(i / (canvas.width - 1)); ctx.fillRect(i, 0, 1, canvas.height); }
  }

  return { View, rampColour, hsColour, drawRamp, fmtLatLon, wrap };
})();
