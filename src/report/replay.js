// platbench report replay: plays each scenario's drawn frames (see src/report/replay.rs).
(function () {
  "use strict";
  function Replay(root) {
    var d = JSON.parse(root.querySelector("script.replay-data").textContent);
    var svg = root.querySelector("svg");
    var scrub = root.querySelector(".scrub");
    var clock = root.querySelector(".clock");
    var button = root.querySelector(".play");
    var speed = root.querySelector(".speed");
    var bodies = svg.querySelectorAll("g.body");
    var paths = svg.querySelectorAll("g.path");
    var plats = svg.querySelectorAll("rect.platform");
    var boxes = root.querySelectorAll(".picker input");
    var marks = root.querySelectorAll(".picker .fault");
    var n = d.runs.length ? d.runs[0].x.length : 0;
    var self = this, k = 0, playing = false, t0 = 0, start = 0;
    function frameOf(i) { return Math.min(i * d.stride, d.frames - 1); }
    function faults(c) {
      var f = c.charCodeAt(0) - 48, out = [];
      d.names.forEach(function (nm) { if (f & nm[0]) out.push(nm[1]); });
      return out.join(", ");
    }
    function show(i) {
      k = Math.max(0, Math.min(n - 1, i));
      scrub.value = k;
      var f = frameOf(k);
      clock.textContent = "frame " + f + " of " + (d.frames - 1) + ", t = " + (f * d.dt).toFixed(3) + " s";
      d.runs.forEach(function (r, j) {
        var m = Math.min(k, r.x.length - 1);
        if (m < 0) return;
        bodies[j].setAttribute("transform", "translate(" + r.x[m] + "," + r.y[m] + ")");
        var why = faults(r.f.charAt(m) || "0");
        bodies[j].classList.toggle("bad", why !== "");
        marks[j].textContent = why ? "(" + why + ")" : "";
      });
      d.platforms.forEach(function (p, j) {
        plats[j].setAttribute("x", p.x[k]);
        plats[j].setAttribute("y", p.y[k]);
      });
    }
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
    button.addEventListener("click", function () { if (playing) pause(); else play(); });
    speed.addEventListener("change", function () { if (playing) { pause(); play(); } });
    scrub.addEventListener("input", function () { pause(); show(parseInt(scrub.value, 10)); });
    boxes.forEach(function (b) {
      b.addEventListener("change", function () {
        var j = parseInt(b.getAttribute("data-k"), 10);
        bodies[j].style.display = paths[j].style.display = b.checked ? "inline" : "none";
      });
    });
    show(0);
    this.root = root; this.n = n; this.data = d;
    this.show = show; this.play = play; this.pause = pause;
    this.frame = function () { return k; };
    this.bodies = bodies; this.plats = plats; this.boxes = boxes;
  }
  var replays = [];
  document.querySelectorAll("div.replay").forEach(function (r) { replays.push(new Replay(r)); });

  function param(name) {
    var m = new RegExp("[#&]" + name + "=([^&]*)").exec(location.hash);
    return m ? decodeURIComponent(m[1]) : null;
  }
  var view = param("view");
  if (view !== null) {
    var r = document.getElementById("replay-" + view);
    if (r) {
      var keep = r;
      Array.prototype.forEach.call(document.body.children, function (c) {
        if (c !== keep && !c.contains(keep) && c.tagName !== "SCRIPT") c.style.display = "none";
      });
      var pic = r.querySelector("svg");
      pic.style.height = "480px";
      pic.style.width = "auto";
      pic.style.maxWidth = "none";
      var title = document.getElementById(view);
      if (title) title.style.display = "block";
      replays.forEach(function (p) {
        if (p.root === r) p.show(parseInt(param("frame") || "0", 10));
      });
    }
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
    // The picker: unticking a configuration hides its character, ticking shows it again.
    var first = replays[0];
    if (first) {
      var box = first.boxes[0];
      var was = box.checked;
      box.checked = false; box.dispatchEvent(new Event("change"));
      var hidden = first.bodies[0].style.display === "none";
      box.checked = true; box.dispatchEvent(new Event("change"));
      out.picker = hidden && first.bodies[0].style.display !== "none";
      box.checked = was; box.dispatchEvent(new Event("change"));
      // Playing: after half a second of (virtual) time the frame has advanced.
      first.root.querySelector(".play").click();
      setTimeout(function () {
        out.played_to = first.frame();
        var r0 = first.data.runs[0], m = Math.min(first.frame(), r0.x.length - 1);
        // The character stands where its trace is at the frame reached.
        out.played_drawn = first.bodies[0].getAttribute("transform") === "translate(" + r0.x[m] + "," + r0.y[m] + ")";
        out.clock = first.root.querySelector(".clock").textContent;
        first.pause();
        var pre = document.createElement("pre");
        pre.id = "selftest";
        pre.textContent = JSON.stringify(out);
        document.body.appendChild(pre);
      }, 500);
    }
  }
})();
