// platbench report replay: plays each scenario's drawn frames (see src/report/replay.rs; the
// data is made by src/report/html_replay_data.rs).
(function () {
  "use strict";
  // A packed channel (html_replay_data.rs, `pack`): differences from the previous value, "d*n"
  // one difference n times; each value divided by `unit`.
  function unpack(s, unit) {
    var out = [], v = 0;
    if (!s) return out;
    s.split(",").forEach(function (tok) {
      var star = tok.indexOf("*");
      var dv = parseInt(star < 0 ? tok : tok.slice(0, star), 10);
      var n = star < 0 ? 1 : parseInt(tok.slice(star + 1), 10);
      for (var i = 0; i < n; i++) { v += dv; out.push(v / unit); }
    });
    return out;
  }
  // Zoom steps and limit: 16 times shows a 0.01-tile gap as a few pixels on the widest picture
  // (80 tiles in about 1150 px: 230 px a tile at 16 times).
  var ZOOM_STEP = 1.25, ZOOM_MAX = 16;
  var hovered = null;
  function Replay(root) {
    var d = JSON.parse(root.querySelector("script.replay-data").textContent);
    var svg = root.querySelector("svg");
    var scrub = root.querySelector(".scrub");
    var clock = root.querySelector(".clock");
    var button = root.querySelector(".play");
    var speed = root.querySelector(".speed");
    var follow = root.querySelector(".follow");
    var count = root.querySelector(".picker .count");
    var state = root.querySelector("table.state tbody");
    var bodies = svg.querySelectorAll("g.body");
    var paths = svg.querySelectorAll("g.path");
    var plats = svg.querySelectorAll("rect.platform");
    var boxes = root.querySelectorAll(".picker input");
    d.runs.forEach(function (r) {
      ["x", "y"].forEach(function (c) { r[c] = unpack(r[c], d.pu); });
      ["vx", "vy", "nx", "ny"].forEach(function (c) { r[c] = unpack(r[c], d.vu); });
    });
    var n = d.runs.length ? d.runs[0].x.length : 0;
    var self = this, k = 0, playing = false, t0 = 0, start = 0;
    var full = svg.getAttribute("viewBox").split(/[ ,]+/).map(parseFloat);
    var vb = { x: full[0], y: full[1], w: full[2], h: full[3] };
    function frameOf(i) { return Math.min(i * d.stride, d.frames - 1); }
    // The character's centre in pixels at drawn frame m, as its transform.
    function at(j, m) {
      var r = d.runs[j];
      var x = (r.x[m] - d.ox) * d.scale, y = (d.oy - r.y[m] - r.h) * d.scale;
      return "translate(" + x.toFixed(1) + "," + y.toFixed(1) + ")";
    }
    function faults(c) {
      var f = c.charCodeAt(0) - 48, out = [];
      d.names.forEach(function (nm) { if (f & nm[0]) out.push(nm[1]); });
      return out.join(", ");
    }
    function shownRuns() {
      var out = [];
      boxes.forEach(function (b, j) { if (b.checked) out.push(j); });
      return out;
    }
    function esc(t) { return t.replace(/&/g, "&amp;").replace(/</g, "&lt;"); }
    function num(v) { return isFinite(v) ? v.toFixed(3) : String(v); }
    // Each shown character's state at drawn frame k, as its trace has it.
    function table() {
      var html = "";
      shownRuns().forEach(function (j) {
        var r = d.runs[j], m = Math.min(k, r.x.length - 1);
        if (m < 0) return;
        var s = (r.s.charCodeAt(m) || 48) - 48, why = faults(r.f.charAt(m) || "0");
        var on = (s & 1 ? "yes: (" + num(r.nx[m]) + ", " + num(r.ny[m]) + ")" : "no") +
          (s & 2 ? ", ladder" : "") + (s & 4 ? ", platform" : "");
        html += "<tr" + (why ? " class=\"bad\"" : "") + "><td><i style=\"background:" +
          bodies[j].getAttribute("stroke") + "\"></i>" + esc(boxes[j].getAttribute("data-run")) +
          (why ? " <span class=\"fault\">(" + why + ")</span>" : "") + "</td><td>" + num(r.x[m]) +
          ", " + num(r.y[m]) + "</td><td>" + num(r.vx[m]) + ", " + num(r.vy[m]) + "</td><td>" + on +
          "</td></tr>";
      });
      state.innerHTML = html;
    }
    function setView(x, y, w) {
      w = Math.max(full[2] / ZOOM_MAX, Math.min(full[2], w));
      var h = w * full[3] / full[2];
      // Keep at least half the view over the picture.
      x = Math.max(full[0] - w / 2, Math.min(full[0] + full[2] - w / 2, x));
      y = Math.max(full[1] - h / 2, Math.min(full[1] + full[3] - h / 2, y));
      vb = { x: x, y: y, w: w, h: h };
      svg.setAttribute("viewBox", [x, y, w, h].map(function (v) { return +v.toFixed(2); }).join(" "));
    }
    // Zooms by `f` keeping picture point (cx, cy) where it is (the view's centre by default).
    function zoom(f, cx, cy) {
      if (cx === undefined) { cx = vb.x + vb.w / 2; cy = vb.y + vb.h / 2; }
      var w = Math.max(full[2] / ZOOM_MAX, Math.min(full[2], vb.w / f)), s = w / vb.w;
      setView(cx - (cx - vb.x) * s, cy - (cy - vb.y) * s, w);
      if (follow.checked) keepInView();
    }
    // Follow: centre the view on the shown characters, zooming out only when they are spread
    // wider than it (with 2 tiles of margin).
    function keepInView() {
      if (vb.w >= full[2]) return;
      var lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
      shownRuns().forEach(function (j) {
        var r = d.runs[j], m = Math.min(k, r.x.length - 1);
        if (m < 0 || !isFinite(r.x[m]) || !isFinite(r.y[m])) return;
        var x = (r.x[m] - d.ox) * d.scale, y = (d.oy - r.y[m] - r.h) * d.scale;
        lo = [Math.min(lo[0], x), Math.min(lo[1], y)];
        hi = [Math.max(hi[0], x), Math.max(hi[1], y)];
      });
      if (lo[0] > hi[0]) return;
      var margin = 2 * d.scale;
      var w = Math.max(vb.w, hi[0] - lo[0] + 2 * margin, (hi[1] - lo[1] + 2 * margin) * full[2] / full[3]);
      var h = w * full[3] / full[2];
      setView((lo[0] + hi[0]) / 2 - w / 2, (lo[1] + hi[1]) / 2 - h / 2, w);
    }
    function show(i) {
      k = Math.max(0, Math.min(n - 1, i));
      scrub.value = k;
      var f = frameOf(k);
      clock.textContent = "frame " + f + " of " + (d.frames - 1) + ", t = " + (f * d.dt).toFixed(3) + " s";
      d.runs.forEach(function (r, j) {
        var m = Math.min(k, r.x.length - 1);
        if (m < 0) return;
        bodies[j].setAttribute("transform", at(j, m));
        bodies[j].classList.toggle("bad", faults(r.f.charAt(m) || "0") !== "");
      });
      d.platforms.forEach(function (p, j) {
        plats[j].setAttribute("x", p.x[k]);
        plats[j].setAttribute("y", p.y[k]);
      });
      table();
      if (follow.checked) keepInView();
    }
    // Trace frame `f` (as a table's link names it): the drawn frame that stands for it (a drawn
    // frame carries the frames since the one before it).
    function showFrame(f) { show(Math.ceil(Math.max(0, f) / d.stride)); }
    // Timers, not animation frames: they also run under a headless browser's virtual time.
    function tick() {
      if (!playing) return;
      var t = t0 + (performance.now() - start) / 1000 * parseFloat(speed.value);
      var i = Math.floor(t / (d.dt * d.stride) + 1e-9);
      if (i >= n - 1) { show(n - 1); pause(); return; }
      if (i !== k) show(i);
      setTimeout(tick, 1000 / 60);
    }
    function play() {
      if (k >= n - 1) show(0);
      playing = true;
      button.textContent = "pause";
      t0 = k * d.stride * d.dt;
      start = performance.now();
      setTimeout(tick, 1000 / 60);
    }
    function pause() { playing = false; button.textContent = "play"; }
    function step(by) { pause(); show(k + by); }
    // The keys a replay answers: arrows step (10 frames with shift), + and - zoom.
    function key(e) {
      var by = e.shiftKey ? 10 : 1;
      if (e.key === "ArrowRight") step(by);
      else if (e.key === "ArrowLeft") step(-by);
      else if (e.key === "+" || e.key === "=") zoom(ZOOM_STEP);
      else if (e.key === "-") zoom(1 / ZOOM_STEP);
      else return;
      e.preventDefault();
    }
    button.addEventListener("click", function () { if (playing) pause(); else play(); });
    speed.addEventListener("change", function () { if (playing) { pause(); play(); } });
    scrub.addEventListener("input", function () { pause(); show(parseInt(scrub.value, 10)); });
    boxes.forEach(function (b) {
      b.addEventListener("change", function () {
        var j = parseInt(b.getAttribute("data-k"), 10);
        bodies[j].style.display = paths[j].style.display = b.checked ? "inline" : "none";
        count.textContent = shownRuns().length;
        table();
      });
    });
    root.querySelector(".zoom-in").addEventListener("click", function () { zoom(ZOOM_STEP); });
    root.querySelector(".zoom-out").addEventListener("click", function () { zoom(1 / ZOOM_STEP); });
    root.querySelector(".zoom-fit").addEventListener("click", function () { setView(full[0], full[1], full[2]); });
    follow.addEventListener("change", function () { if (follow.checked) keepInView(); });
    root.addEventListener("keydown", function (e) {
      // The scrubber and the other inputs keep their own keys.
      if (/^(INPUT|SELECT|BUTTON|SUMMARY)$/.test(e.target.tagName)) return;
      key(e);
    });
    root.addEventListener("mouseenter", function () { hovered = self; });
    root.addEventListener("mouseleave", function () { if (hovered === self) hovered = null; });
    // A point of the window in picture units (through the SVG's own transform, which accounts
    // for a picture drawn smaller than its box).
    function toPicture(x, y) {
      var pt = svg.createSVGPoint();
      pt.x = x; pt.y = y;
      return pt.matrixTransform(svg.getScreenCTM().inverse());
    }
    // The wheel zooms when the picture was clicked (the replay has the focus) or with Ctrl, so
    // that it scrolls the page otherwise.
    svg.addEventListener("wheel", function (e) {
      if (!(e.ctrlKey || root.contains(document.activeElement))) return;
      e.preventDefault();
      var p = toPicture(e.clientX, e.clientY);
      zoom(e.deltaY < 0 ? ZOOM_STEP : 1 / ZOOM_STEP, p.x, p.y);
    }, { passive: false });
    // Dragging pans (and stops following).
    var drag = null;
    svg.addEventListener("pointerdown", function (e) {
      if (e.button !== 0) return;
      drag = { x: e.clientX, y: e.clientY, vx: vb.x, vy: vb.y };
      root.focus({ preventScroll: true });
      // A pointer the browser does not know (a synthetic one) cannot be captured.
      try { svg.setPointerCapture(e.pointerId); } catch (err) { /* panning still works */ }
    });
    svg.addEventListener("pointermove", function (e) {
      if (!drag) return;
      var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) < 3) return;
      follow.checked = false;
      // Picture units per screen pixel (the view's scale, whatever the letterboxing).
      var s = 1 / svg.getScreenCTM().a;
      setView(drag.vx - dx * s, drag.vy - dy * s, vb.w);
    });
    svg.addEventListener("pointerup", function () { drag = null; });
    svg.addEventListener("pointercancel", function () { drag = null; });
    show(0);
    this.root = root; this.n = n; this.data = d;
    this.show = show; this.showFrame = showFrame; this.play = play; this.pause = pause;
    this.key = key; this.at = at; this.zoom = zoom;
    this.view = function () { return vb; };
    this.full = full;
    this.frame = function () { return k; };
    this.bodies = bodies; this.plats = plats; this.boxes = boxes;
  }
  var replays = [];
  document.querySelectorAll("div.replay").forEach(function (r) { replays.push(new Replay(r)); });
  // Arrow keys over a replay step it even when the focus is elsewhere (not in a field).
  document.addEventListener("keydown", function (e) {
    if (e.defaultPrevented || !hovered) return;
    var t = document.activeElement;
    if (t && /^(INPUT|SELECT|TEXTAREA)$/.test(t.tagName)) return;
    if (t && t.classList && t.classList.contains("replay") && t !== hovered.root) return;
    hovered.key(e);
  });

  function param(name) {
    var m = new RegExp("[#&]" + name + "=([^&]*)").exec(location.hash);
    return m ? decodeURIComponent(m[1]) : null;
  }
  function has(name) { return new RegExp("[#&]" + name + "(=|&|$)").test(location.hash); }
  // `#view=REPLAY_ID&frame=N`: that replay at trace frame N (a table value's link), scrolled
  // to and focused; `&show=BACKEND CONFIG` also ticks that configuration; `&alone` hides the
  // rest of the page (for a screenshot).
  function go() {
    var view = param("view");
    if (view === null) return;
    var r = document.getElementById("replay-" + view);
    if (!r) return;
    var p = null;
    replays.forEach(function (q) { if (q.root === r) p = q; });
    var want = param("show");
    if (want !== null) {
      p.boxes.forEach(function (b) {
        if (b.getAttribute("data-run") === want && !b.checked) {
          b.checked = true;
          b.dispatchEvent(new Event("change"));
        }
      });
    }
    var f = parseInt(param("frame") || "0", 10);
    p.pause();
    p.showFrame(isNaN(f) ? 0 : f);
    var title = document.getElementById(view);
    if (has("alone")) {
      // Everything but the replay, its title and their ancestors.
      for (var e = r; e && e !== document.body; e = e.parentElement) {
        Array.prototype.forEach.call(e.parentElement.children, function (c) {
          if (c !== e && c !== title && c.tagName !== "SCRIPT") c.style.display = "none";
        });
      }
      var pic = r.querySelector("svg");
      pic.style.height = "480px";
      pic.style.width = "auto";
      pic.style.maxWidth = "none";
    } else {
      (title || r).scrollIntoView();
    }
    r.focus({ preventScroll: true });
  }
  go();
  window.addEventListener("hashchange", go);
  // A link to the address already shown changes no hash: follow it again all the same.
  document.addEventListener("click", function (e) {
    var a = e.target.closest && e.target.closest("a[href^='#view=']");
    if (a && a.getAttribute("href") === location.hash) go();
  });

  function report(id, out) {
    var pre = document.createElement("pre");
    pre.id = id;
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  // `#measure`: the page's layout at this window size, for tests/browser/page.rs.
  if (location.hash === "#measure") {
    var bottom = function (sel) {
      var e = document.querySelector(sel);
      return e ? e.getBoundingClientRect().bottom + window.scrollY : null;
    };
    report("measure", {
      scroll_width: document.documentElement.scrollWidth,
      inner_width: window.innerWidth,
      height: document.body.scrollHeight,
      toc_bottom: bottom("#toc"),
      first_h2_bottom: bottom("h2"),
      verdict_bottom: bottom("#verdict"),
      verdict_table_bottom: bottom("table.verdict"),
      scorecard_heading_bottom: bottom("#scorecard"),
      scorecard_bottom: bottom("table.scorecard")
    });
  }
  if (location.hash === "#selftest") {
    var out = { replays: replays.length, scrub_moved: 0, platforms: 0, platforms_moved: 0, errors: [] };
    var pos = function (e) { return e.getAttribute("transform") + e.getAttribute("x") + e.getAttribute("y"); };
    replays.forEach(function (p) {
      try {
        p.show(0);
        var before = [], moved = false;
        p.bodies.forEach(function (b) { before.push(pos(b)); });
        var pb = [], pmoved = false;
        p.plats.forEach(function (b) { pb.push(pos(b)); });
        for (var i = 1; i < p.n; i++) {
          var sc = p.root.querySelector(".scrub");
          sc.value = i;
          sc.dispatchEvent(new Event("input"));
          p.bodies.forEach(function (b, j) { if (pos(b) !== before[j]) moved = true; });
          p.plats.forEach(function (b, j) { if (pos(b) !== pb[j]) pmoved = true; });
        }
        if (moved) out.scrub_moved++;
        if (p.plats.length) { out.platforms++; if (pmoved) out.platforms_moved++; }
        p.show(0);
      } catch (e) { out.errors.push(String(e)); }
    });
    var first = replays[0];
    if (first) {
      // The picker: unticking a configuration hides its character and its state row, ticking
      // shows them again.
      var box = first.boxes[0];
      var was = box.checked;
      var rows = function () { return first.root.querySelectorAll("table.state tbody tr").length; };
      box.checked = true; box.dispatchEvent(new Event("change"));
      var withIt = rows();
      box.checked = false; box.dispatchEvent(new Event("change"));
      var hidden = first.bodies[0].style.display === "none" && rows() === withIt - 1;
      box.checked = true; box.dispatchEvent(new Event("change"));
      out.picker = hidden && first.bodies[0].style.display !== "none" && rows() === withIt;
      // The state table: the first row gives the trace's position at the frame.
      first.show(3);
      var cells = first.root.querySelectorAll("table.state tbody tr:first-child td");
      out.state = Array.prototype.map.call(cells, function (c) { return c.textContent; });
      out.state_x = first.data.runs[0].x[3].toFixed(3);
      box.checked = was; box.dispatchEvent(new Event("change"));
      // Keys: with the focus on the replay, and with the mouse over it.
      first.show(5);
      var press = function (target, key) {
        target.dispatchEvent(new KeyboardEvent("keydown", { key: key, bubbles: true, cancelable: true }));
        return first.frame();
      };
      out.keys = [press(first.root, "ArrowRight"), press(first.root, "ArrowLeft")];
      first.root.dispatchEvent(new MouseEvent("mouseenter"));
      document.body.focus();
      out.keys.push(press(document, "ArrowRight"));
      first.root.dispatchEvent(new MouseEvent("mouseleave"));
      out.keys.push(press(document, "ArrowRight"));
      // Zoom and follow: zoomed in four steps and played to the end, the shown characters are
      // still in view.
      first.show(0);
      first.root.querySelector(".zoom-in").click();
      out.zoom = +(first.full[2] / first.view().w).toFixed(3);
      for (var z = 0; z < 3; z++) first.root.querySelector(".zoom-in").click();
      first.show(first.n - 1);
      var v = first.view(), inView = true;
      first.boxes.forEach(function (b, j) {
        if (!b.checked) return;
        var t = /translate\(([-\d.]+),([-\d.]+)\)/.exec(first.bodies[j].getAttribute("transform"));
        var x = parseFloat(t[1]), y = parseFloat(t[2]);
        if (x < v.x || x > v.x + v.w || y < v.y || y > v.y + v.h) inView = false;
      });
      out.followed = inView && v.w < first.full[2];
      // Dragging pans by the distance dragged (in picture units) and stops following.
      var svg = first.root.querySelector("svg"), before = first.view().x;
      var ptr = function (type, x) {
        svg.dispatchEvent(new PointerEvent(type, { clientX: x, clientY: 10, button: 0, pointerId: 1, bubbles: true }));
      };
      ptr("pointerdown", 100); ptr("pointermove", 60); ptr("pointerup", 60);
      var dragged = 40 / svg.getScreenCTM().a;
      out.panned = Math.abs(first.view().x - (before + dragged)) < 0.1 &&
        !first.root.querySelector(".follow").checked;
      first.root.querySelector(".follow").checked = true;
      first.root.querySelector(".zoom-fit").click();
      out.fit = first.view().w === first.full[2];
      first.show(0);
      // Playing: after half a second of (virtual) time the frame has advanced.
      first.root.querySelector(".play").click();
      setTimeout(function () {
        out.played_to = first.frame();
        var r0 = first.data.runs[0], m = Math.min(first.frame(), r0.x.length - 1);
        // The character stands where its trace is at the frame reached.
        out.played_drawn = first.bodies[0].getAttribute("transform") === first.at(0, m);
        out.clock = first.root.querySelector(".clock").textContent;
        first.pause();
        report("selftest", out);
      }, 500);
    }
  }
})();
