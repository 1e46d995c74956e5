/* SPDX-License-Identifier: Apache-2.0 */
/* The bench page of atv312d (docs/web.md): one tile per drive from /api/bench, kept live by the
 * state events of /api/events; a drive's page (#drive/N) with its trend, its frame counters and
 * the control surface, whose buttons post the same commands as `atv312d ctl`. */
"use strict";

const TOKEN_KEY = "atv312d-token";
const RETRY_MS = 2000; // a closed event stream is opened again after this

// The colour of each LED of a CANopen card (the manuals' signalling tables); DeviceNet's MS and
// NS are bicolour and say their colour in their state ("flashing-green").
const LED_COLOURS = { RUN: "green", ERR: "red", OK: "green", COM: "yellow" };

// What the NS LED of a DeviceNet card says of its connections (docs/devicenet.md, LEDs).
const DEVICENET_CONNECTION = {
  off: "not online (duplicate MAC ID check)",
  "flashing-green": "online, no connection",
  green: "connected",
  "flashing-red": "I/O connection timed out",
  red: "faulted (duplicate MAC ID or bus off)",
};

const FRAME_COUNTERS = {
  received: "received",
  sent: "sent",
  dropped: "dropped",
  sdo_requests: "SDO requests",
  sdo_aborts: "SDO aborts",
  emcy: "EMCY",
  explicit_requests: "explicit requests",
  error_responses: "error responses",
  io_messages: "I/O messages",
  fragments: "fragments",
  timeouts: "timeouts",
};

// Status word bit 9, "remote": 0 under local control (docs/atv312d.md, "Control surface").
const STATUSWORD_REMOTE = 0x0200;

const page = {
  bench: null, // /api/bench
  state: null, // the last /api/state or state event
  histories: new Map(), // node -> Trend.History
  tiles: new Map(), // node -> the bench's tile
  driveTile: null, // the drive page's tile
  driveNode: null, // the node the drive page shows, null on the bench
};

// ---- small helpers -------------------------------------------------------------------------------

function el(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (key === "class") node.className = value;
    else if (key === "text") node.textContent = value;
    else node.setAttribute(key, value);
  }
  node.append(...children);
  return node;
}

function driveOf(node) {
  return page.bench.drives.find((d) => d.node === node);
}

function devicenet() {
  return page.bench.protocol === "devicenet";
}

function nodeTitle(node) {
  return devicenet() ? `MAC ID ${node}` : `Node ${node}`;
}

function showProblem(text) {
  const problem = document.getElementById("problem");
  problem.textContent = text;
  problem.hidden = text === "";
}

async function getJson(path) {
  const response = await fetch(path, { cache: "no-store" });
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
  return response.json();
}

// ---- LEDs ----------------------------------------------------------------------------------------

/* An LED's pattern and colour from a node's state: a CANopen card's "<name>_led" is a CiA 303-3
 * pattern ("single flash"), a DeviceNet card's "ms"/"ns" is colour and pattern ("flashing-red"). */
function ledLook(name, node) {
  const key = name.toLowerCase();
  if (`${key}_led` in node) {
    const pattern = node[`${key}_led`];
    return { pattern: pattern.replace(/ /g, "-"), colour: LED_COLOURS[name] || "green", words: pattern };
  }
  const value = node[key] || "off";
  const [pattern, colour] = value.startsWith("flashing-") ? ["flashing", value.slice(9)]
    : value === "off" ? ["off", ""] : ["on", value];
  return { pattern, colour, words: value.replace(/-/g, " ") };
}

function renderLed(led, name, node) {
  const look = ledLook(name, node);
  const label = `${name} ${look.words}`;
  if (led.dataset.pattern === look.pattern && led.dataset.colour === look.colour) return;
  led.dataset.pattern = look.pattern;
  led.dataset.colour = look.colour;
  led.setAttribute("aria-label", label);
  led.title = label;
}

// ---- tiles ---------------------------------------------------------------------------------------

/* The facts a tile lists: [key, label]; the values come from fieldText(). */
function tileFields() {
  const first = devicenet() ? [["connection", "connection"], ["supervisor", "supervisor"]] : [["nmt", "NMT"]];
  return [
    ...first,
    ["cia402", "CiA 402"],
    ["reference", "reference"],
    ["speed", "speed"],
    ["current", "current"],
    ["torque", "torque"],
    ["fault", "fault"],
  ];
}

function fieldText(key, node, drive) {
  // A plain node (a PLC300, an I/O node: "kind":"node") has its NMT state and LEDs, no drive.
  if (node.kind === "node" && key !== "nmt") return "—";
  switch (key) {
    case "connection":
      return DEVICENET_CONNECTION[node.ns] || node.ns;
    case "reference":
      return node.reference_rpm === undefined ? "—" : `${node.reference_rpm} rpm`;
    case "speed":
      return `${node.speed_rpm} rpm`;
    case "current":
      return `${node.current_a.toFixed(1)} A`;
    case "torque":
      return `${node.torque_percent} %`;
    case "fault": {
      if (node.fault === null) return "none";
      const known = drive.faults.find((f) => f.code === node.fault);
      return known ? `${node.fault} (${known.name})` : node.fault;
    }
    default:
      return String(node[key]);
  }
}

function buildTile(drive, linked) {
  const title = `${nodeTitle(drive.node)} · ${drive.model}`;
  // On the bench a tile is named and opens the drive's page; the drive's page has its own title.
  const heading = linked
    ? el("h3", { class: "tile-title" }, el("a", { href: `#drive/${drive.node}`, text: title }))
    : "";

  const display = SevenSegment.create();
  const leds = new Map();
  const ledRow = el("div", { class: "leds" });
  for (const name of drive.leds) {
    const led = el("span", { class: "led", role: "img", "data-led": name });
    leds.set(name, led);
    const caption = el("span", { class: "led-name", text: name, "aria-hidden": "true" });
    ledRow.append(el("span", { class: "led-box" }, led, caption));
  }
  const face = el("div", { class: "face" }, el("div", { class: "display-window" }, display), ledRow);

  const fields = new Map();
  const list = el("dl", { class: "facts" });
  for (const [key, label] of tileFields()) {
    const value = el("dd", { "data-field": key, text: "…" });
    fields.set(key, value);
    list.append(el("div", {}, el("dt", { text: label }), value));
  }

  const root = el("article", { class: "tile", "data-node": String(drive.node), "data-present": "false" },
    heading, face, list);
  return { root, display, leds, fields, drive };
}

function renderTile(tile, node) {
  tile.root.dataset.present = String(node !== undefined);
  if (node === undefined) {
    SevenSegment.render(tile.display, "");
    return;
  }
  SevenSegment.render(tile.display, node.display ?? "");
  tile.root.dataset.display = node.display ?? "";
  tile.root.dataset.fault = node.fault ?? "";
  tile.root.dataset.cia402 = node.cia402;
  for (const [name, led] of tile.leds) renderLed(led, name, node);
  for (const [key, value] of tile.fields) {
    const text = fieldText(key, node, tile.drive);
    if (value.textContent !== text) value.textContent = text;
  }
}

function buildBench() {
  const tiles = document.getElementById("tiles");
  tiles.replaceChildren();
  page.tiles.clear();
  for (const drive of page.bench.drives) {
    const tile = buildTile(drive, true);
    page.tiles.set(drive.node, tile);
    page.histories.set(drive.node, new Trend.History());
    tiles.append(tile.root);
  }
  document.getElementById("bus-interface").textContent = page.bench.interface;
  document.getElementById("bus-protocol").textContent = devicenet() ? "DeviceNet" : "CANopen";
  document.title = `atv312d ${page.bench.interface}`;
}

// ---- the state ---------------------------------------------------------------------------------

function renderBus(bus) {
  const state = document.getElementById("bus-state");
  state.textContent = bus.state;
  state.dataset.state = bus.state;
  document.getElementById("bus-fps").textContent = bus.frames_per_second.toFixed(1);
  document.getElementById("bus-received").textContent = bus.frames_received;
  document.getElementById("bus-sent").textContent = bus.frames_sent;
}

function applyState(state) {
  if (!state.ok) return;
  page.state = state;
  renderBus(state.bus);
  const byNode = new Map(state.nodes.map((n) => [n.node, n]));
  for (const [nodeId, tile] of page.tiles) {
    const node = byNode.get(nodeId);
    renderTile(tile, node);
    if (node !== undefined) page.histories.get(nodeId).add(state.time_ms, node);
  }
  if (page.driveNode !== null) renderDrivePage(byNode.get(page.driveNode));
  document.body.dataset.ready = "true";
}

/* The state events, opened again after RETRY_MS when the stream closes for good (the browser
 * itself reconnects after a network error). */
function listen() {
  const link = document.getElementById("link");
  const events = new EventSource("api/events");
  events.addEventListener("open", () => {
    link.textContent = "live";
    link.dataset.live = "true";
  });
  events.addEventListener("state", (event) => applyState(JSON.parse(event.data)));
  events.addEventListener("error", () => {
    link.textContent = "connection lost: retrying…";
    link.dataset.live = "false";
    if (events.readyState === EventSource.CLOSED) setTimeout(listen, RETRY_MS);
  });
}

// ---- a drive's page --------------------------------------------------------------------------------

function renderCounters(frames) {
  const body = document.querySelector("#counters tbody");
  const rows = Object.entries(frames);
  if (body.rows.length !== rows.length) {
    body.replaceChildren(...rows.map(([key]) =>
      el("tr", {}, el("th", { scope: "row", text: FRAME_COUNTERS[key] || key }), el("td", { "data-counter": key }))));
  }
  for (const [key, value] of rows) body.querySelector(`[data-counter="${key}"]`).textContent = value;
}

function renderInputs(drive, node) {
  const holder = document.getElementById("inputs");
  if (holder.dataset.node !== String(drive.node)) {
    holder.dataset.node = String(drive.node);
    holder.replaceChildren(...drive.inputs.map((input) =>
      el("button", { type: "button", class: "input", "data-input": input, "aria-pressed": "false", text: input })));
    if (drive.inputs.length === 0) holder.append(el("span", { class: "note", text: "none on this model" }));
  }
  const on = new Set(node ? node.inputs : []);
  for (const button of holder.querySelectorAll("button")) {
    button.setAttribute("aria-pressed", String(on.has(button.dataset.input)));
  }
}

function renderDrivePage(node) {
  const drive = driveOf(page.driveNode);
  renderTile(page.driveTile, node);
  renderInputs(drive, node);
  if (node === undefined) return;
  renderCounters(node.frames);
  document.getElementById("remote").textContent =
    node.statusword & STATUSWORD_REMOTE ? "now: network control (status word bit 9 = 1)"
      : "now: local control (status word bit 9 = 0)";
  Trend.draw(document.getElementById("trend"), page.histories.get(page.driveNode), page.state.time_ms);
}

function openDrivePage(nodeId) {
  const drive = driveOf(nodeId);
  if (drive === undefined) {
    showProblem(`no drive ${nodeId} on this bench`);
    openBench();
    return;
  }
  showProblem("");
  page.driveNode = nodeId;
  document.getElementById("drive-title").textContent = `${nodeTitle(nodeId)} · ${drive.model}`;
  page.driveTile = buildTile(drive, false);
  document.getElementById("drive-tile").replaceChildren(page.driveTile.root);
  const faults = document.getElementById("fault-code");
  faults.replaceChildren(...drive.faults.map((f) => el("option", { value: f.code, text: `${f.code}: ${f.name}` })));
  document.getElementById("command").textContent = "";
  setReply("", "");
  document.getElementById("bench-view").hidden = true;
  document.getElementById("drive-view").hidden = false;
  const state = page.state && page.state.nodes.find((n) => n.node === nodeId);
  renderDrivePage(state);
}

function openBench() {
  page.driveNode = null;
  document.getElementById("drive-view").hidden = true;
  document.getElementById("bench-view").hidden = false;
}

function route() {
  const match = /^#drive\/(\d+)$/.exec(location.hash);
  if (match) openDrivePage(Number(match[1]));
  else openBench();
}

// ---- actions -------------------------------------------------------------------------------------

function setReply(text, ok) {
  const reply = document.getElementById("reply");
  reply.textContent = text;
  reply.dataset.ok = ok;
}

function setupActions() {
  const fields = document.getElementById("control-fields");
  const tokenForm = document.getElementById("token-form");
  fields.disabled = !page.bench.actions;
  document.getElementById("actions-off").hidden = page.bench.actions;
  tokenForm.hidden = !(page.bench.actions && page.bench.token_required && !sessionStorage.getItem(TOKEN_KEY));
  tokenForm.addEventListener("submit", (event) => {
    event.preventDefault();
    sessionStorage.setItem(TOKEN_KEY, document.getElementById("token").value.trim());
    tokenForm.hidden = true;
  });
  fields.addEventListener("click", (event) => {
    const button = event.target.closest("button");
    if (button === null || page.driveNode === null) return;
    if (button.dataset.input !== undefined) {
      const on = button.getAttribute("aria-pressed") === "true";
      sendCommand(`input ${page.driveNode} ${button.dataset.input} ${on ? "off" : "on"}`);
    } else if (button.dataset.command !== undefined) {
      sendCommand(button.dataset.command
        .replace("{node}", page.driveNode)
        .replace("{fault}", document.getElementById("fault-code").value)
        .replace("{load}", document.getElementById("load").value));
    }
  });
}

/* Posts one control command and shows its one-line answer, as `atv312d ctl` prints it. */
async function sendCommand(command) {
  document.getElementById("command").textContent = command;
  setReply("…", "");
  const headers = { "Content-Type": "application/json" };
  const token = sessionStorage.getItem(TOKEN_KEY);
  if (page.bench.token_required && token) headers["X-Atv312d-Token"] = token;
  let answer;
  try {
    const response = await fetch("api/command", { method: "POST", headers, body: JSON.stringify({ command }) });
    answer = await response.json();
    if (response.status === 403 && page.bench.token_required) {
      sessionStorage.removeItem(TOKEN_KEY);
      document.getElementById("token-form").hidden = false;
    }
  } catch (error) {
    answer = { ok: false, error: `no answer from the daemon (${error.message})` };
  }
  // A refused command's answer carries the control surface's own line; other refusals (the
  // token, actions off) only their reason.
  if (answer.ok) setReply(answer.reply, "true");
  else setReply(answer.reply ?? `error: ${answer.error}`, "false");
}

// ---- start ---------------------------------------------------------------------------------------

/* For the browser tests and the curious: the page's data, read-only copies. */
window.atv312d = {
  trend(node) {
    const history = page.histories.get(node);
    return history ? { samples: history.samples.slice(), markers: history.markers.slice() } : null;
  },
  state() {
    return page.state;
  },
};

async function start() {
  try {
    page.bench = await getJson("api/bench");
  } catch (error) {
    showProblem(`cannot read the bench from the daemon: ${error.message}`);
    return;
  }
  buildBench();
  setupActions();
  try {
    applyState(await getJson("api/state"));
  } catch (error) {
    showProblem(`cannot read the drives' state: ${error.message}`);
  }
  window.addEventListener("hashchange", route);
  window.addEventListener("resize", () => {
    if (page.driveNode !== null && page.state !== null) {
      renderDrivePage(page.state.nodes.find((n) => n.node === page.driveNode));
    }
  });
  route();
  listen();
}

start();
