/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's front-panel display: four seven-segment digits with decimal points, drawn in SVG
 * from the text the daemon reports ("nSt", "rdY", "50.0", "OHF"). Only the characters a seven-
 * segment display can show exist; an Altivar code uses nothing else. */
"use strict";

const SevenSegment = (() => {
  const SVG = "http://www.w3.org/2000/svg";
  const DIGITS = 4; // the Altivar 312's display
  // One digit's geometry, in SVG units: width, height, segment thickness, gap between segments.
  const W = 50, H = 90, T = 9, GAP = 1.5;
  const PITCH = W + 16; // from one digit to the next, room for the decimal point
  const SLANT = -6; // degrees: the italic lean of a real display
  const LEFT = T / 2, RIGHT = W - T / 2, TOP = T / 2, MID = H / 2, BOTTOM = H - T / 2;

  // The segments a..g (a top, then clockwise, g the middle bar) of each character the display
  // shows. Letters a seven-segment display has in one case only stand for both cases.
  const GLYPHS = {
    "0": "abcdef", "1": "bc", "2": "abdeg", "3": "abcdg", "4": "bcfg",
    "5": "acdfg", "6": "acdefg", "7": "abc", "8": "abcdefg", "9": "abcdfg",
    A: "abcefg", b: "cdefg", C: "adef", c: "deg", d: "bcdeg", E: "adefg", F: "aefg",
    G: "acdef", H: "bcefg", h: "cefg", I: "ef", i: "e", J: "bcd", L: "def", n: "ceg",
    O: "abcdef", o: "cdeg", P: "abefg", q: "abcfg", r: "eg", S: "acdfg", t: "defg", U: "bcdef",
    u: "cde", Y: "bcdfg", "-": "g", "_": "d", " ": "",
  };

  function glyph(ch) {
    if (ch in GLYPHS) return GLYPHS[ch];
    if (ch.toLowerCase() in GLYPHS) return GLYPHS[ch.toLowerCase()];
    if (ch.toUpperCase() in GLYPHS) return GLYPHS[ch.toUpperCase()];
    return ""; // nothing a seven-segment display could show: left dark
  }

  function horizontal(y, x0, x1) {
    const h = T / 2;
    return [[x0, y], [x0 + h, y - h], [x1 - h, y - h], [x1, y], [x1 - h, y + h], [x0 + h, y + h]];
  }

  function vertical(x, y0, y1) {
    const h = T / 2;
    return [[x, y0], [x + h, y0 + h], [x + h, y1 - h], [x, y1], [x - h, y1 - h], [x - h, y0 + h]];
  }

  const SEGMENTS = {
    a: horizontal(TOP, LEFT + GAP, RIGHT - GAP),
    b: vertical(RIGHT, TOP + GAP, MID - GAP),
    c: vertical(RIGHT, MID + GAP, BOTTOM - GAP),
    d: horizontal(BOTTOM, LEFT + GAP, RIGHT - GAP),
    e: vertical(LEFT, MID + GAP, BOTTOM - GAP),
    f: vertical(LEFT, TOP + GAP, MID - GAP),
    g: horizontal(MID, LEFT + GAP, RIGHT - GAP),
  };

  /* The text as display cells: one character each, a '.' lighting the point of the cell before
   * it; right-aligned on the four digits (more cells than digits widen the display). */
  function cells(text) {
    const out = [];
    for (const ch of text) {
      if (ch === "." && out.length > 0 && !out[out.length - 1].point) {
        out[out.length - 1].point = true;
      } else if (ch === ".") {
        out.push({ segments: "", point: true });
      } else {
        out.push({ segments: glyph(ch), point: false });
      }
    }
    while (out.length < DIGITS) out.unshift({ segments: "", point: false });
    return out;
  }

  function element(name, attributes) {
    const el = document.createElementNS(SVG, name);
    for (const [key, value] of Object.entries(attributes)) el.setAttribute(key, value);
    return el;
  }

  function drawDigit(group, cell, index) {
    const digit = element("g", { transform: `translate(${index * PITCH + 12} 4) skewX(${SLANT})` });
    for (const [name, points] of Object.entries(SEGMENTS)) {
      const lit = cell.segments.includes(name);
      digit.appendChild(element("polygon", {
        points: points.map((p) => p.join(",")).join(" "),
        class: lit ? "segment on" : "segment",
        "data-segment": name,
      }));
    }
    digit.appendChild(element("circle", {
      cx: W + 6, cy: BOTTOM, r: T / 2 + 0.5, class: cell.point ? "segment on" : "segment",
      "data-segment": "dp",
    }));
    group.appendChild(digit);
  }

  /* An SVG element showing text; render() changes what it shows. */
  function create() {
    const svg = element("svg", { class: "seven-segment", role: "img", focusable: "false" });
    render(svg, "");
    return svg;
  }

  function render(svg, text) {
    if (svg.dataset.text === text) return;
    svg.dataset.text = text;
    svg.setAttribute("aria-label", text === "" ? "display dark" : `display ${text}`);
    const all = cells(text);
    svg.setAttribute("viewBox", `0 0 ${all.length * PITCH + 10} ${H + 8}`);
    svg.replaceChildren();
    all.forEach((cell, i) => drawDigit(svg, cell, i));
  }

  return { create, render };
})();
