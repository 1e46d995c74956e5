/* SPDX-License-Identifier: Apache-2.0 */
/* A drive's trend of the last minute on a canvas: speed (reference and actual, rpm) above,
 * current (A, left scale) and torque (%, right scale) below, the state changes as marked lines.
 * Plain canvas rather than a charting library: four series on a fixed 60 s window are a few
 * dozen lines, and the page stays a handful of files to embed with nothing to vendor. */
"use strict";

const Trend = (() => {
  const WINDOW_MS = 60000;
  const SERIES = [
    { key: "reference", label: "reference (rpm)", colour: "#1f6fd1", panel: 0, dash: [6, 4] },
    { key: "speed", label: "speed (rpm)", colour: "#0b3d91", panel: 0, dash: [] },
    { key: "current", label: "current (A)", colour: "#d9731a", panel: 1, dash: [] },
    { key: "torque", label: "torque (%)", colour: "#8a3fb5", panel: 1, dash: [3, 3], right: true },
  ];
  const MARKER_COLOUR = "#6b6b6b";
  const AXIS_COLOUR = "#9aa0a6";
  const TEXT_COLOUR = "#333";
  const FONT = "11px system-ui, sans-serif";
  const LABEL_ROWS = 3, LABEL_HEIGHT = 12; // the state changes' labels, above the plot
  const MARGIN = { left: 48, right: 44, top: 22 + LABEL_ROWS * LABEL_HEIGHT, bottom: 22, between: 26 };

  /* The last minute of samples of one drive, and the moments its state changed. */
  class History {
    constructor() {
      this.samples = []; // {t, reference, speed, current, torque} with t in ms (the daemon's clock)
      this.markers = []; // {t, label}
      this.last = null; // the state words of the previous sample, to see changes
    }

    add(t, node) {
      // A clock that went back is another daemon's (restarted): its minute starts afresh.
      if (this.samples.length > 0 && t < this.samples[this.samples.length - 1].t) {
        this.samples = [];
        this.markers = [];
        this.last = null;
      }
      const words = stateWords(node);
      if (this.last !== null) {
        for (const [what, value] of Object.entries(words)) {
          if (value !== this.last[what]) this.markers.push({ t, label: value });
        }
      }
      this.last = words;
      this.samples.push({
        t,
        reference: node.reference_rpm ?? null,
        speed: node.speed_rpm,
        current: node.current_a,
        torque: node.torque_percent,
      });
      const oldest = t - WINDOW_MS;
      while (this.samples.length > 0 && this.samples[0].t < oldest) this.samples.shift();
      while (this.markers.length > 0 && this.markers[0].t < oldest) this.markers.shift();
    }
  }

  /* What a marker names: the CiA 402 state, and the NMT state (CANopen) or the Control
   * supervisor's (DeviceNet). */
  function stateWords(node) {
    const words = { cia402: node.cia402 };
    if (node.nmt !== undefined) words.nmt = `NMT ${node.nmt}`;
    if (node.supervisor !== undefined) words.supervisor = `supervisor ${node.supervisor}`;
    return words;
  }

  /* The smallest 1, 2, 2.5 or 5 x 10^n at least v: a scale's end. */
  function niceCeil(v) {
    if (v <= 0) return 0;
    const power = 10 ** Math.floor(Math.log10(v));
    for (const m of [1, 2, 2.5, 5, 10]) {
      if (m * power >= v) return m * power;
    }
    return 10 * power;
  }

  function range(samples, keys, floor) {
    let lo = 0, hi = floor;
    for (const s of samples) {
      for (const k of keys) {
        if (s[k] === null) continue;
        lo = Math.min(lo, s[k]);
        hi = Math.max(hi, s[k]);
      }
    }
    return { lo: -niceCeil(-lo), hi: niceCeil(hi) };
  }

  function draw(canvas, history, now) {
    const ratio = window.devicePixelRatio || 1;
    const width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== Math.round(width * ratio)) canvas.width = Math.round(width * ratio);
    if (canvas.height !== Math.round(height * ratio)) canvas.height = Math.round(height * ratio);
    const ctx = canvas.getContext("2d");
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, height);
    ctx.font = FONT;

    const plotW = width - MARGIN.left - MARGIN.right;
    const panelH = (height - MARGIN.top - MARGIN.bottom - MARGIN.between) / 2;
    const panels = [
      { top: MARGIN.top, scales: [range(history.samples, ["reference", "speed"], 100)] },
      {
        top: MARGIN.top + panelH + MARGIN.between,
        scales: [range(history.samples, ["current"], 1), range(history.samples, ["torque"], 100)],
      },
    ];
    const x = (t) => MARGIN.left + plotW * (1 - (now - t) / WINDOW_MS);
    const y = (panel, scale, v) => panel.top + panelH * (1 - (v - scale.lo) / (scale.hi - scale.lo));

    drawLegend(ctx);
    panels.forEach((panel, i) => drawAxes(ctx, panel, panelH, plotW, width, i === 1));
    drawTimeAxis(ctx, panels[1].top + panelH, plotW);

    drawMarkers(ctx, history.markers, x, panels[1].top + panelH, MARGIN.left + plotW);
    ctx.save();
    ctx.beginPath();
    ctx.rect(MARGIN.left, MARGIN.top, plotW, height - MARGIN.top - MARGIN.bottom);
    ctx.clip();
    for (const series of SERIES) {
      const panel = panels[series.panel];
      const scale = panel.scales[series.right ? 1 : 0];
      ctx.strokeStyle = series.colour;
      ctx.lineWidth = 2;
      ctx.setLineDash(series.dash);
      ctx.beginPath();
      let pen = false;
      for (const s of history.samples) {
        if (s[series.key] === null) {
          pen = false;
          continue;
        }
        const px = x(s.t), py = y(panel, scale, s[series.key]);
        if (pen) ctx.lineTo(px, py);
        else ctx.moveTo(px, py);
        pen = true;
      }
      ctx.stroke();
    }
    ctx.restore();
    ctx.setLineDash([]);
  }

  function drawLegend(ctx) {
    let lx = MARGIN.left;
    ctx.textBaseline = "middle";
    for (const series of SERIES) {
      ctx.strokeStyle = series.colour;
      ctx.lineWidth = 2;
      ctx.setLineDash(series.dash);
      ctx.beginPath();
      ctx.moveTo(lx, 9);
      ctx.lineTo(lx + 18, 9);
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.fillStyle = TEXT_COLOUR;
      ctx.textAlign = "left";
      ctx.fillText(series.label, lx + 22, 9);
      lx += 30 + ctx.measureText(series.label).width;
    }
  }

  function drawAxes(ctx, panel, panelH, plotW, width, twoScales) {
    ctx.strokeStyle = AXIS_COLOUR;
    ctx.lineWidth = 1;
    ctx.strokeRect(MARGIN.left + 0.5, panel.top + 0.5, plotW, panelH);
    ctx.fillStyle = TEXT_COLOUR;
    ctx.textBaseline = "middle";
    panel.scales.forEach((scale, i) => {
      const right = twoScales && i === 1;
      ctx.textAlign = right ? "left" : "right";
      const tx = right ? width - MARGIN.right + 4 : MARGIN.left - 4;
      for (const v of [scale.lo, (scale.lo + scale.hi) / 2, scale.hi]) {
        const py = panel.top + panelH * (1 - (v - scale.lo) / (scale.hi - scale.lo));
        ctx.fillText(String(Math.round(v * 10) / 10), tx, py);
      }
    });
    const zero = panel.scales[0];
    if (zero.lo < 0) {
      const py = panel.top + panelH * (1 - (0 - zero.lo) / (zero.hi - zero.lo));
      ctx.beginPath();
      ctx.moveTo(MARGIN.left, py);
      ctx.lineTo(MARGIN.left + plotW, py);
      ctx.stroke();
    }
  }

  function drawTimeAxis(ctx, bottom, plotW) {
    ctx.fillStyle = TEXT_COLOUR;
    ctx.textAlign = "center";
    ctx.textBaseline = "top";
    for (let s = 60; s >= 0; s -= 10) {
      const px = MARGIN.left + plotW * (1 - s / 60);
      ctx.fillText(s === 0 ? "now" : `-${s} s`, px, bottom + 5);
    }
  }

  /* Each state change: a dotted line through both panels, its label above the plot on the first
   * of the label rows where it overlaps no other label; left of its line near the right edge. */
  function drawMarkers(ctx, markers, x, bottom, plotRight) {
    const rowEnds = new Array(LABEL_ROWS).fill(-Infinity);
    ctx.strokeStyle = MARKER_COLOUR;
    ctx.fillStyle = MARKER_COLOUR;
    ctx.lineWidth = 1;
    ctx.textBaseline = "bottom";
    for (const m of markers) {
      const px = Math.round(x(m.t)) + 0.5;
      if (px < MARGIN.left) continue;
      const width = ctx.measureText(m.label).width;
      const leftward = px + 3 + width > plotRight;
      const start = leftward ? px - 3 - width : px + 3;
      let row = rowEnds.findIndex((end) => end < start);
      if (row < 0) row = LABEL_ROWS - 1;
      rowEnds[row] = start + width + 6;
      const labelY = MARGIN.top - 2 - row * LABEL_HEIGHT;
      ctx.setLineDash([2, 3]);
      ctx.beginPath();
      ctx.moveTo(px, labelY - LABEL_HEIGHT + 2);
      ctx.lineTo(px, bottom);
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.textAlign = leftward ? "right" : "left";
      ctx.fillText(m.label, leftward ? px - 3 : px + 3, labelY);
    }
  }

  return { History, draw };
})();
