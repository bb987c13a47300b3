// drillstring live: the page of the live display. The server sends SI numbers with, for each
// quantity, its label, the unit it is shown in and the factor from SI to that unit; the page
// multiplies by the factor and never converts on its own. The tracks keep the last window of
// time in fixed-size ring buffers, so the page's memory does not grow with the run.
"use strict";

(function () {
  const stats = {
    renders: 0, frames: 0, bytes: 0, t: 0, rows: 0, drawn: 0, buffered: 0, capacity: 0, replies: [], errors: [],
    connected: false,
  };
  window.drillstringStats = stats;

  let hello = null;
  let ring = null;
  let tracks = [];     // {channel, graph, value}
  let profiles = [];   // {channel, graph}
  let state = null;
  let dirty = false;
  let nextId = 1;
  let socket = null;

  const $ = (id) => document.getElementById(id);

  // ------------------------------------------------------------------ ring buffers of the tracks

  class Ring {
    constructor(capacity, names) {
      this.capacity = capacity;
      this.count = 0;
      this.head = 0;   // the slot the next row goes to
      this.columns = {};
      for (const name of names) this.columns[name] = new Float64Array(capacity);
    }
    push(rows) {
      const t = rows.t || [];
      for (let i = 0; i < t.length; i++) {
        for (const name in this.columns) {
          const column = rows[name];
          const v = column === undefined ? NaN : column[i];
          this.columns[name][this.head] = v === null ? NaN : v;
        }
        this.head = (this.head + 1) % this.capacity;
        this.count = Math.min(this.count + 1, this.capacity);
      }
    }
    last(name) {
      if (!this.count) return NaN;
      return this.columns[name][(this.head - 1 + this.capacity) % this.capacity];
    }
    // rows [t, value * factor] of the channel, oldest first, from time `since` on
    series(name, factor, since) {
      const out = [];
      const t = this.columns.t, v = this.columns[name];
      for (let k = 0; k < this.count; k++) {
        const i = (this.head - this.count + k + this.capacity) % this.capacity;
        if (t[i] < since) continue;
        const value = v[i];
        out.push([t[i], Number.isFinite(value) ? value * factor : null]);
      }
      return out;
    }
  }

  // ------------------------------------------------------------------ building the page

  function fmt(x, digits) {
    return Number.isFinite(x) ? x.toPrecision(digits || 4) : "-";
  }

  function build(message) {
    hello = message;
    $("name").textContent = message.name || "";
    const names = ["t"].concat(message.tracks.map((c) => c.name));
    ring = new Ring(message.points + 64, names);
    const box = $("tracks");
    box.innerHTML = "<h2>Log tracks (last " + message.window_s + " s)</h2>";
    tracks = message.tracks.map((c) => {
      const row = document.createElement("div");
      row.className = "track " + c.group;
      row.dataset.channel = c.name;
      row.innerHTML = '<div class="label">' + c.label + "<small>" + c.unit + '</small><span class="value">-</span></div>' +
        '<div class="plot"></div>';
      box.appendChild(row);
      const graph = new Dygraph(row.querySelector(".plot"), [[0, null]], {
        labels: ["t", c.label], legend: "never", drawPoints: false, strokeWidth: 1.2,
        colors: [c.group === "downhole" ? "#b3400a" : "#1c5d99"], axisLabelFontSize: 10,
        xAxisHeight: 16, yAxisLabelWidth: 44, dateWindow: [0, message.window_s],
        axes: { x: { drawAxis: true } }, rightGap: 4,
      });
      return { channel: c, graph: graph, value: row.querySelector(".value") };
    });
    const side = $("profiles");
    side.innerHTML = "<h2>Along the string (depth in " + message.depth.unit + ")</h2>";
    profiles = message.profiles.map((c) => {
      const div = document.createElement("div");
      div.className = "profile";
      div.dataset.channel = c.name;
      div.innerHTML = '<div class="label">' + c.label + " (" + c.unit + ')</div><div class="plot"></div>';
      side.appendChild(div);
      const graph = new Dygraph(div.querySelector(".plot"), [[0, null]], {
        labels: ["depth", c.label], legend: "never", strokeWidth: 1.2, colors: ["#2b7a3d"],
        axisLabelFontSize: 10, xAxisHeight: 16, yAxisLabelWidth: 44, rightGap: 4,
      });
      return { channel: c, graph: graph };
    });
    buildControls(message.controls);
    $("changes").textContent = "";
  }

  function buildControls(controls) {
    const box = $("setpoints");
    box.innerHTML = "";
    for (const c of controls) {
      const div = document.createElement("div");
      div.className = "control";
      div.dataset.key = c.key;
      const label = document.createElement("label");
      label.textContent = c.label + (c.unit ? " (" + c.unit + ")" : "");
      div.appendChild(label);
      if (c.kind === "slider") {
        const lo = c.min * c.factor, hi = c.max * c.factor;
        const slider = document.createElement("input");
        const number = document.createElement("input");
        slider.type = "range"; number.type = "number";
        for (const input of [slider, number]) {
          input.min = lo; input.max = hi; input.step = "any"; input.value = Number((c.value * c.factor).toPrecision(5));
          input.dataset.key = c.key;
          div.appendChild(input);
        }
        slider.addEventListener("input", () => { number.value = slider.value; });
        const send = (input) => {
          const shown = parseFloat(input.value);
          if (!Number.isFinite(shown)) { show("not a number: " + input.value, true); return; }
          slider.value = number.value = input.value;
          command({ type: "set", key: c.key, value: shown / c.factor });
        };
        slider.addEventListener("change", () => send(slider));
        number.addEventListener("change", () => send(number));
      } else {
        const select = document.createElement("select");
        select.dataset.key = c.key;
        const names = c.value === null ? [""].concat(c.choices) : c.choices;
        for (const name of names) {
          const option = document.createElement("option");
          option.value = name; option.textContent = name || "(as configured)";
          option.selected = name === (c.value || "");
          select.appendChild(option);
        }
        select.addEventListener("change", () => {
          if (!select.value) return;
          command(c.kind === "preset" ? { type: "preset", value: select.value }
            : { type: "set", key: c.key, value: select.value });
        });
        div.appendChild(select);
      }
      box.appendChild(div);
    }
  }

  function show(text, error) {
    const box = $("message");
    box.textContent = text;
    box.className = error ? "error" : "";
  }

  // ------------------------------------------------------------------ the connection

  function command(message) {
    message.id = nextId++;
    if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(message));
    return message.id;
  }
  window.drillstringCommand = command;

  function receive(text) {
    stats.bytes += text.length;
    const message = JSON.parse(text);
    if (message.type === "hello") {
      build(message);
    } else if (message.type === "reset") {
      build(message);
      show("the run started again", false);
    } else if (message.type === "frame") {
      frame(message);
    } else if (message.type === "reply") {
      stats.replies.push(message);
      if (stats.replies.length > 50) stats.replies.shift();
      if (!message.ok) show(message.message, true);
      else if (message.command === "record") show("recorded to " + message.result, false);
      else if (message.command === "set") show("set", false);
      else if (message.command === "preset") show("set " + message.result.join(", "), false);
    }
  }

  function frame(message) {
    stats.frames += 1;
    const status = message.status;
    stats.t = status.t;
    $("time").textContent = status.t.toFixed(1);
    $("rtf").textContent = status.rtf === null ? "-" : status.rtf.toFixed(2) + " (asked " + status.speed + ")";
    const speed = $("speed"), asked = String(status.speed);
    if (speed.value !== asked && document.activeElement !== speed) {
      if (![...speed.options].some((o) => o.value === asked)) speed.add(new Option(asked + "x", asked));
      speed.value = asked;
    }
    $("run-status").textContent = status.status !== "success" ? status.status + ": " + status.message
      : (status.paused ? "paused" : "running");
    if (message.rows && message.rows.t) {
      ring.push(message.rows);
      stats.rows += message.rows.t.length;
      dirty = true;
    }
    if (message.state) {
      state = message.state;
      $("stick").classList.toggle("on", state.bit_stuck);
      $("bounce").classList.toggle("on", state.bit_bounce);
      dirty = true;
    }
    if (message.verdict) verdict(message.verdict);
    if (message.events) {
      for (const e of message.events) {
        const line = document.createElement("div");
        line.textContent = "t = " + e.t.toFixed(2) + " s: " + e.key + " = " + e.value;
        $("changes").prepend(line);
        const choice = document.querySelector('select[data-key="' + e.key + '"]');
        if (choice && typeof e.value === "string") choice.value = e.value;  // a preset's type
      }
    }
  }

  function verdict(v) {
    const box = $("verdict");
    let text = "last window " + v.window[0].toFixed(0) + "-" + v.window[1].toFixed(0) + " s: stick-slip " +
      v.verdict + "; " + v.texts.join(", ");
    if (v.coupled !== undefined) text += "; " + v.coupled;
    box.textContent = text;
    box.className = "verdict " + v.verdict;
  }

  function render() {
    requestAnimationFrame(render);
    if (!dirty || !hello) return;
    dirty = false;
    const end = Math.max(ring.last("t"), hello.window_s);
    const since = end - hello.window_s;
    for (const tr of tracks) {
      const c = tr.channel;
      const data = ring.series(c.name, c.factor, since);
      if (data.length) tr.graph.updateOptions({ file: data, dateWindow: [since, end] });
      stats.drawn = data.length;
      tr.value.textContent = fmt(ring.last(c.name) * c.factor, 4);
    }
    if (state) {
      for (const p of profiles) {
        const c = p.channel;
        const z = state[c.group], v = state[c.name];
        if (!z || !v) continue;
        const data = z.map((x, i) => [x * hello.depth.factor, v[i] === null ? null : v[i] * c.factor]);
        p.graph.updateOptions({ file: data });
      }
    }
    stats.renders += 1;
    stats.buffered = ring.count;
    stats.capacity = ring.capacity;
  }

  function connect() {
    const url = (location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws";
    socket = new WebSocket(url);
    socket.onopen = () => { stats.connected = true; };
    socket.onmessage = (event) => receive(event.data);
    socket.onclose = () => {
      stats.connected = false;
      $("run-status").textContent = "disconnected (the server stopped)";
    };
  }

  $("pause").addEventListener("click", () => command({ type: "pause" }));
  $("resume").addEventListener("click", () => command({ type: "resume" }));
  $("reset").addEventListener("click", () => command({ type: "reset" }));
  $("record").addEventListener("click", () => { show("recording...", false); command({ type: "record" }); });
  $("speed").addEventListener("change", () => command({ type: "speed", value: $("speed").value }));
  window.addEventListener("error", (event) => stats.errors.push(String(event.message)));

  connect();
  requestAnimationFrame(render);
})();
