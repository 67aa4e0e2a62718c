// throwmap viewer: plays the motion stored in #viewer-data (see throwmap.viz.viewer) on two canvases.
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("viewer-data").textContent);
  if (!D) { return; }  // a page without a player (tables only)
  const q = D.q, n = D.n, P = D.parts.length;
  const root = document.getElementById("player");
  const scene = document.getElementById("scene"), sc = scene.getContext("2d");
  const orbitCv = document.getElementById("orbit"), oc = orbitCv.getContext("2d");
  const frameSlider = document.getElementById("frame"), throwSlider = document.getElementById("throw");
  const playBtn = document.getElementById("play"), speedSel = document.getElementById("speed");
  const readout = document.getElementById("readout");
  const O = D.orbit;

  // contact offsets per frame
  const cStart = new Int32Array(n + 1);
  for (let i = 0; i < n; i++) { cStart[i + 1] = cStart[i] + D.cc[i]; }

  // the orbit steps one can jump to: those whose motion is in the page, with their first frame
  const jumps = [];  // {step, frame}
  if (O) {
    const first = new Map();
    for (let f = 0; f < n; f++) { const s = D.step[f]; if (s >= 0 && !first.has(s)) { first.set(s, f); } }
    for (let s = 0; s < O.throw.length; s++) { if (first.has(s)) { jumps.push({ step: s, frame: first.get(s) }); } }
  }

  let frame = 0, playing = false, speed = 1, simT = 0, lastTs = null;

  // ---------------------------------------------------------------- the scene
  const [vx0, vx1, vy0, vy1] = D.view;
  const W = scene.width, H = scene.height;
  const scale = Math.min(W / (vx1 - vx0), H / (vy1 - vy0));
  const ox = (W - scale * (vx1 - vx0)) / 2 - scale * vx0;
  const oy = (H + scale * (vy1 - vy0)) / 2 + scale * vy0;
  const X = (x) => ox + scale * x, Y = (y) => oy - scale * y;

  function polygon(ctx, flat, c, s, tx, ty) {  // flat: quantised body/arm-frame points, turned by (c, s), moved by (tx, ty) in m
    ctx.beginPath();
    for (let j = 0; j < flat.length; j += 2) {
      const u = flat[j] * q, v = flat[j + 1] * q;
      const x = tx + c * u - s * v, y = ty + s * u + c * v;
      if (j === 0) { ctx.moveTo(X(x), Y(y)); } else { ctx.lineTo(X(x), Y(y)); }
    }
    ctx.closePath();
  }

  function niceLength(width) {  // the largest 1-2-5 length <= width / 5
    const target = Math.max(width, 1e-6) / 5, e = Math.floor(Math.log10(target));
    let best = Math.pow(10, e);
    for (const m of [1, 2, 5]) { if (m * Math.pow(10, e) <= target * (1 + 1e-12)) { best = m * Math.pow(10, e); } }
    return best;
  }
  const barLen = niceLength(vx1 - vx0);
  const barText = barLen >= 1 ? barLen + " m" : barLen >= 0.01 ? +(100 * barLen).toPrecision(6) + " cm" : +(1000 * barLen).toPrecision(6) + " mm";

  function drawScene(f) {
    sc.fillStyle = "#ffffff"; sc.fillRect(0, 0, W, H);
    const a = D.arm[f] * q, c = Math.cos(a), s = Math.sin(a);
    sc.lineWidth = 1;
    for (const p of D.arm_pieces) { polygon(sc, p, c, s, 0, 0); sc.fillStyle = "#8a8a8a"; sc.fill(); sc.strokeStyle = "#8a8a8a"; sc.stroke(); }
    for (const p of D.fixture_pieces) { polygon(sc, p, c, s, 0, 0); sc.fillStyle = "#555555"; sc.fill(); sc.strokeStyle = "#555555"; sc.stroke(); }
    sc.beginPath(); sc.arc(X(0), Y(0), 5, 0, 2 * Math.PI); sc.fillStyle = "#222"; sc.fill();  // the joint
    for (let p = 0; p < P; p++) {
      const pose = D.poses[p], x = pose[3 * f] * q, y = pose[3 * f + 1] * q, phi = pose[3 * f + 2] * q;
      polygon(sc, D.parts[p].w, Math.cos(phi), Math.sin(phi), x, y);
      sc.fillStyle = D.parts[p].color; sc.fill();
      sc.strokeStyle = "#222"; sc.lineWidth = 1.2; sc.stroke();
      sc.beginPath(); sc.arc(X(x), Y(y), 2.5, 0, 2 * Math.PI); sc.fillStyle = "#111"; sc.fill();
    }
    sc.fillStyle = "#e00000";
    for (let k = cStart[f]; k < cStart[f + 1]; k++) {
      sc.beginPath(); sc.arc(X(D.cp[2 * k] * q), Y(D.cp[2 * k + 1] * q), 3, 0, 2 * Math.PI); sc.fill();
    }
    // scale bar and text
    sc.strokeStyle = "#222"; sc.lineWidth = 2; sc.beginPath();
    sc.moveTo(16, H - 16); sc.lineTo(16 + scale * barLen, H - 16); sc.stroke();
    sc.fillStyle = "#222"; sc.font = "12px sans-serif"; sc.fillText(barText, 16, H - 22);
    const st = D.step[f];
    const lines = ["t = " + (D.t0 + f / D.fps).toFixed(3) + " s"];
    if (O && st >= 0) { lines.push("throw " + O.throw[st] + (O.phase[st] ? " (" + O.phase[st] + ")" : "")); }
    if (D.labels[D.label[f]]) { lines.push(D.labels[D.label[f]]); }
    sc.font = "13px sans-serif";
    lines.forEach((t, i) => sc.fillText(t, 12, 20 + 16 * i));
    return lines;
  }

  // ---------------------------------------------------------------- the orbit plot
  const OW = orbitCv.width, OH = orbitCv.height, m = { l: 58, r: 12, t: 24, b: 40 };
  let tMin = 0, tMax = 1, xMin = 0, xMax = 1;
  if (O && O.throw.length) {
    tMin = Math.min(...O.throw); tMax = Math.max(...O.throw, tMin + 1);
    const xs = O.x.flat().map((v) => v * q * 100);
    xMin = Math.min(...xs); xMax = Math.max(...xs);
    const pad = Math.max(0.05 * (xMax - xMin), 0.5); xMin -= pad; xMax += pad;
  }
  const PX = (k) => m.l + (OW - m.l - m.r) * (k - tMin) / (tMax - tMin);
  const PY = (x) => OH - m.b - (OH - m.t - m.b) * (x - xMin) / (xMax - xMin);

  function ticks(lo, hi, count) {
    const raw = (hi - lo) / count, e = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((k) => k * e).find((v) => v >= raw) || raw;
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9; v += step) { out.push(+v.toPrecision(10)); }
    return out;
  }

  function drawOrbit(f) {
    oc.fillStyle = "#ffffff"; oc.fillRect(0, 0, OW, OH);
    oc.font = "12px sans-serif"; oc.fillStyle = "#222";
    if (!O || !O.throw.length) { oc.fillText("no orbit recorded with this motion", m.l, OH / 2); return; }
    oc.strokeStyle = "#e6e6e6"; oc.lineWidth = 1;
    for (const v of ticks(xMin, xMax, 6)) {
      oc.beginPath(); oc.moveTo(m.l, PY(v)); oc.lineTo(OW - m.r, PY(v)); oc.stroke();
      oc.textAlign = "right"; oc.fillText(String(v), m.l - 5, PY(v) + 4); oc.textAlign = "left";
    }
    for (const k of ticks(tMin, tMax, 6)) {
      if (k !== Math.round(k)) { continue; }
      oc.beginPath(); oc.moveTo(PX(k), m.t); oc.lineTo(PX(k), OH - m.b); oc.stroke();
      oc.fillText(String(k), PX(k) - 4, OH - m.b + 14);
    }
    oc.fillText("throw number", OW / 2 - 36, OH - 8);
    oc.save(); oc.translate(14, OH / 2 + 50); oc.rotate(-Math.PI / 2); oc.fillText("x (cm, arm frame)", 0, 0); oc.restore();
    const sw = O.phase.indexOf("tilt");
    if (sw >= 0) {
      oc.strokeStyle = "#999"; oc.setLineDash([4, 3]); oc.beginPath();
      oc.moveTo(PX(O.throw[sw] + 0.5), m.t); oc.lineTo(PX(O.throw[sw] + 0.5), OH - m.b); oc.stroke(); oc.setLineDash([]);
      oc.fillStyle = "#666"; oc.fillText("switch", PX(O.throw[sw] + 0.5) + 3, m.t + 12);
    }
    const st = D.step[f];
    if (st >= 0) {  // the throw being played
      oc.fillStyle = "rgba(255, 200, 0, 0.35)";
      const w = Math.max(4, PX(tMin + 1) - PX(tMin));
      oc.fillRect(PX(O.throw[st]) - w / 2, m.t, w, OH - m.t - m.b);
    }
    for (let p = 0; p < P; p++) {
      oc.strokeStyle = D.parts[p].color; oc.fillStyle = D.parts[p].color; oc.lineWidth = 1.2; oc.beginPath();
      for (let s = 0; s < O.throw.length; s++) {
        const px = PX(O.throw[s]), py = PY(O.x[s][p] * q * 100);
        if (s === 0) { oc.moveTo(px, py); } else { oc.lineTo(px, py); }
      }
      oc.stroke();
      for (let s = 0; s < O.throw.length; s++) {
        oc.beginPath(); oc.arc(PX(O.throw[s]), PY(O.x[s][p] * q * 100), 2.2, 0, 2 * Math.PI); oc.fill();
      }
      if (st >= 0) {
        oc.beginPath(); oc.arc(PX(O.throw[st]), PY(O.x[st][p] * q * 100), 6, 0, 2 * Math.PI);
        oc.lineWidth = 2; oc.strokeStyle = "#111"; oc.stroke();
      }
    }
    oc.strokeStyle = "#222"; oc.lineWidth = 1; oc.strokeRect(m.l, m.t, OW - m.l - m.r, OH - m.t - m.b);
  }

  // ---------------------------------------------------------------- state
  function currentJump(f) {
    let j = -1;
    for (let i = 0; i < jumps.length; i++) { if (jumps[i].frame <= f) { j = i; } }
    return j;
  }

  function show(f) {
    frame = Math.max(0, Math.min(n - 1, Math.round(f)));
    const lines = drawScene(frame);
    drawOrbit(frame);
    frameSlider.value = String(frame);
    const j = currentJump(frame);
    if (j >= 0) { throwSlider.value = String(j); }
    root.dataset.frame = String(frame);
    root.dataset.step = String(D.step[frame]);
    readout.textContent = lines.join("   ") + "   frame " + (frame + 1) + "/" + n;
  }

  function setPlaying(on) {
    playing = on && n > 1;
    if (playing && frame >= n - 1) { frame = 0; }
    simT = frame / D.fps; lastTs = null;
    playBtn.innerHTML = playing ? "&#x2016; pause" : "&#x25B6; play";
    root.dataset.playing = String(playing);
    if (playing) { requestAnimationFrame(tick); }
  }

  function tick(ts) {
    if (!playing) { return; }
    if (lastTs !== null) { simT += speed * (ts - lastTs) / 1000; }
    lastTs = ts;
    const f = Math.floor(simT * D.fps);
    if (f >= n - 1) { show(n - 1); setPlaying(false); return; }
    if (f !== frame) { show(f); }
    requestAnimationFrame(tick);
  }

  function jumpBy(dj) {
    if (!jumps.length) { return; }
    let j = currentJump(frame);
    if (dj < 0 && j >= 0 && jumps[j].frame < frame) { dj += 1; }  // back to the start of this throw first
    j = Math.max(0, Math.min(jumps.length - 1, j + dj));
    setPlaying(false); show(jumps[j].frame);
  }

  frameSlider.max = String(n - 1);
  throwSlider.max = String(Math.max(0, jumps.length - 1));
  throwSlider.disabled = jumps.length === 0;
  frameSlider.addEventListener("input", () => { setPlaying(false); show(Number(frameSlider.value)); });
  throwSlider.addEventListener("input", () => {
    const j = jumps[Number(throwSlider.value)];
    if (j) { setPlaying(false); show(j.frame); }
  });
  playBtn.addEventListener("click", () => setPlaying(!playing));
  document.getElementById("step-back").addEventListener("click", () => { setPlaying(false); show(frame - 1); });
  document.getElementById("step-fwd").addEventListener("click", () => { setPlaying(false); show(frame + 1); });
  document.getElementById("prev-throw").addEventListener("click", () => jumpBy(-1));
  document.getElementById("next-throw").addEventListener("click", () => jumpBy(1));
  speedSel.addEventListener("change", () => { speed = Number(speedSel.value); simT = frame / D.fps; lastTs = null; });
  orbitCv.addEventListener("click", (ev) => {
    if (!jumps.length) { return; }
    const r = orbitCv.getBoundingClientRect(), k = tMin + (ev.clientX - r.left - m.l) / (OW - m.l - m.r) * (tMax - tMin);
    let best = 0;
    jumps.forEach((j, i) => { if (Math.abs(O.throw[j.step] - k) < Math.abs(O.throw[jumps[best].step] - k)) { best = i; } });
    setPlaying(false); show(jumps[best].frame);
  });
  document.addEventListener("keydown", (ev) => {
    if (ev.target && ev.target.tagName === "SELECT") { return; }
    if (ev.key === " ") { ev.preventDefault(); setPlaying(!playing); }
    else if (ev.key === "ArrowLeft") { setPlaying(false); show(frame - 1); }
    else if (ev.key === "ArrowRight") { setPlaying(false); show(frame + 1); }
  });
  const esc = (text) => String(text).replace(/[&<>"]/g, (ch) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[ch]);
  document.getElementById("legend").innerHTML = D.parts.map((p, i) =>
    '<span><i style="background:' + esc(p.color) + '"></i>' + (P > 1 ? "part " + i + ": " : "") + esc(p.name) + "</span>").join("") +
    '<span><i style="background:#e00000"></i>contacts</span><span>source: ' + esc(D.source) + ", " + n + " frames at " +
    D.fps.toFixed(3).replace(/\.?0+$/, "") + " per simulated second</span>";
  show(0);
})();
