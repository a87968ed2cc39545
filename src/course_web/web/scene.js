// What the pages draw: turtlesim's canvas and fake_tb3 from above, from the view's frames (see
// course_web.frames). No socket and no keys here: the live page (view.js) feeds it frames from /ws;
// a page that plays recorded frames back would feed it the same, with the same markup (index.html's
// #waiting, sections #turtlesim and #tb3 with their canvases and numbers) and view.css's layout.
// Plain JavaScript, no library: every file comes from this server.
'use strict';
window.courseScene = (function () {
  const TS_SIZE = 500;                 // turtlesim's canvas, pixels
  const TS_PX_PER_METER = 45;
  const SCAN_RED = 'rgb(230,20,20)';   // the laser points, as fake_tb3's own picture draws them
  const ROBOT_BLUE = 'rgb(30,90,200)';
  const VIEW_MARGIN = 0.5;             // metres around what the TurtleBot3 view shows
  const TURTLE_COLOURS = [['#226e34', '#5caa54'], ['#785028', '#be8c46'], ['#1e5a6e', '#50a0aa'],
                          ['#5a641e', '#aab43c'], ['#463c6e', '#8c78b4'], ['#823228', '#d26e50']];

  // What tests and the benchmark read: frames received and, per drawn pose, when it was drawn.
  const stats = {frames: 0, turtlesimFrames: 0, tb3Frames: 0, tb3Poses: 0, scans: 0, drawn: [], tb3ToPixel: null,
                 tb3TrailLength: 0};
  window.courseWeb = stats;
  const clock = () => performance.timeOrigin + performance.now();
  function recordDrawn(what, x) {
    const entry = [what, x, clock(), null];
    stats.drawn.push(entry);
    if (stats.drawn.length > 20000) stats.drawn.splice(0, 5000);
    requestAnimationFrame(() => { entry[3] = clock(); });
  }

  const $ = (id) => document.getElementById(id);
  function showWaiting() { $('waiting').hidden = !($('turtlesim').hidden && $('tb3').hidden); }

  // ---------------------------------------------------------------- turtlesim
  const ts = {ctx: $('turtlesim-canvas').getContext('2d'), path: null, turtles: new Map()};

  function fillPath(r, g, b) {
    const data = ts.path.data;
    for (let i = 0; i < data.length; i += 4) { data[i] = r; data[i + 1] = g; data[i + 2] = b; data[i + 3] = 255; }
  }

  // turtlesim's pen: aliased, square caps; a pixel takes the colour when its centre lies in the
  // stroke rectangle (the segment widened by the width and lengthened by half of it at each end).
  function drawPathLine(x0, y0, x1, y1, r, g, b, width) {
    const half = width / 2, dx = x1 - x0, dy = y1 - y0, length = Math.hypot(dx, dy);
    const ux = length > 0 ? dx / length : 1, uy = length > 0 ? dy / length : 0;
    const reach = half * Math.SQRT2 + 1;
    const colLo = Math.max(0, Math.floor(Math.min(x0, x1) - reach));
    const colHi = Math.min(TS_SIZE - 1, Math.ceil(Math.max(x0, x1) + reach));
    const rowLo = Math.max(0, Math.floor(Math.min(y0, y1) - reach));
    const rowHi = Math.min(TS_SIZE - 1, Math.ceil(Math.max(y0, y1) + reach));
    const data = ts.path.data;
    for (let row = rowLo; row <= rowHi; row++) {
      const ry = row - y0;
      for (let col = colLo; col <= colHi; col++) {
        const cx = col - x0, along = cx * ux + ry * uy, across = ry * ux - cx * uy;
        if (along >= -half && along < length + half && across >= -half && across < half) {
          const i = (row * TS_SIZE + col) * 4;
          data[i] = r; data[i + 1] = g; data[i + 2] = b; data[i + 3] = 255;
        }
      }
    }
  }

  function drawTurtle(ctx, turtle) {
    const [name, x, y, theta, icon] = turtle;
    const px = x * TS_PX_PER_METER, py = TS_SIZE - 1 - y * TS_PX_PER_METER;
    const [shell, centre] = TURTLE_COLOURS[icon % TURTLE_COLOURS.length];
    ctx.save();
    ctx.translate(px, py);
    ctx.rotate(-theta);  // canvas rows grow downwards, theta turns counter-clockwise
    ctx.fillStyle = '#96c86e';
    for (const [u, v] of [[7, 9], [7, -9], [-8, 9], [-8, -9]]) { ctx.beginPath(); ctx.arc(u, v, 3.5, 0, 2 * Math.PI); ctx.fill(); }
    ctx.beginPath(); ctx.ellipse(-14, 0, 2.5, 2, 0, 0, 2 * Math.PI); ctx.fill();
    ctx.beginPath(); ctx.ellipse(13.5, 0, 5, 4, 0, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = shell; ctx.beginPath(); ctx.ellipse(-1, 0, 12, 9.5, 0, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = centre; ctx.beginPath(); ctx.ellipse(-1, 0, 7.5, 5.5, 0, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = '#141414';
    for (const v of [2, -2]) { ctx.beginPath(); ctx.arc(15.5, v, 1, 0, 2 * Math.PI); ctx.fill(); }
    ctx.restore();
    ctx.font = '12px sans-serif';
    ctx.textAlign = 'center';
    ctx.lineWidth = 3;
    ctx.strokeStyle = 'rgba(255,255,255,0.8)';
    ctx.strokeText(name, px, py + 34);
    ctx.fillStyle = '#111';
    ctx.fillText(name, px, py + 34);
  }

  function drawTurtlesim() {
    const ctx = ts.ctx;
    ctx.putImageData(ts.path, 0, 0);
    for (const turtle of ts.turtles.values()) drawTurtle(ctx, turtle);
  }

  async function turtlesimPart(part) {
    $('turtlesim').hidden = !part.present;
    if (!part.present) { ts.path = null; ts.turtles.clear(); return; }
    if (part.canvas) {
      const image = new Image();
      image.src = part.canvas;
      await image.decode();
      const scratch = document.createElement('canvas');
      scratch.width = image.width; scratch.height = image.height;
      const sctx = scratch.getContext('2d');
      sctx.drawImage(image, 0, 0);
      ts.path = sctx.getImageData(0, 0, TS_SIZE, TS_SIZE);
    }
    if (!ts.path) return;
    for (const op of part.ops) {
      if (op[0] === 'fill') fillPath(op[1], op[2], op[3]);
      else drawPathLine(op[1], op[2], op[3], op[4], op[5], op[6], op[7], op[8]);
    }
    // All the turtles, or those that changed and the names of those killed since the last frame.
    if (part.all) ts.turtles.clear();
    for (const name of part.gone || []) ts.turtles.delete(name);
    for (const turtle of part.turtles) ts.turtles.set(turtle[0], turtle);
    drawTurtlesim();
    const first = ts.turtles.get('turtle1');
    if (first) recordDrawn('turtle1', first[1]);
  }

  // ---------------------------------------------------------------- fake_tb3
  const tb = {canvas: $('tb3-canvas'), ctx: $('tb3-canvas').getContext('2d'), world: null, body: null,
              trail: [], scan: [], pose: null, view: null, background: document.createElement('canvas')};
  tb.background.width = tb.canvas.width; tb.background.height = tb.canvas.height;

  function wanted(view, x, y) {
    return view && x >= view.x0 && x <= view.x0 + view.size && y >= view.y0 && y <= view.y0 + view.size;
  }

  // The square of world the canvas shows: the world's obstacles (or 4 m around the start in an
  // empty world), widened to keep the robot and its path in sight.
  function chooseView() {
    const b = tb.world.bounds;
    let [x0, y0, x1, y1] = b ? b : [-2, -2, 2, 2];
    const points = tb.trail.concat(tb.pose ? [[tb.pose[0], tb.pose[1]]] : []);
    for (const [x, y] of points) { x0 = Math.min(x0, x - 1); y0 = Math.min(y0, y - 1); x1 = Math.max(x1, x + 1); y1 = Math.max(y1, y + 1); }
    const size = Math.max(x1 - x0, y1 - y0) + 2 * VIEW_MARGIN;
    tb.view = {x0: (x0 + x1 - size) / 2, y0: (y0 + y1 - size) / 2, size: size, scale: tb.canvas.width / size};
    stats.tb3ToPixel = toPixel;
    drawBackground();
  }

  function toPixel(x, y) {
    const v = tb.view;
    return [(x - v.x0) * v.scale, (v.y0 + v.size - y) * v.scale];
  }

  function drawBackground() {
    const ctx = tb.background.getContext('2d');
    const v = tb.view, w = tb.background.width;
    ctx.fillStyle = 'rgb(250,250,250)'; ctx.fillRect(0, 0, w, w);
    ctx.strokeStyle = 'rgb(225,225,225)'; ctx.lineWidth = 1;
    for (let g = Math.ceil(v.x0); g <= v.x0 + v.size; g++) { const [p] = toPixel(g, 0); ctx.beginPath(); ctx.moveTo(p, 0); ctx.lineTo(p, w); ctx.stroke(); }
    for (let g = Math.ceil(v.y0); g <= v.y0 + v.size; g++) { const [, p] = toPixel(0, g); ctx.beginPath(); ctx.moveTo(0, p); ctx.lineTo(w, p); ctx.stroke(); }
    for (const [kind, data] of tb.world.shapes) {
      ctx.fillStyle = kind === 'hole' ? 'rgb(250,250,250)' : 'rgb(110,110,110)';
      ctx.beginPath();
      if (kind === 'circle') { const [px, py] = toPixel(data[0], data[1]); ctx.arc(px, py, data[2] * v.scale, 0, 2 * Math.PI); }
      else data.forEach(([x, y], i) => { const [px, py] = toPixel(x, y); if (i) ctx.lineTo(px, py); else ctx.moveTo(px, py); });
      ctx.fill();
    }
    drawTrail(0);
  }

  function drawTrail(from) {
    if (tb.trail.length < 2) return;
    const ctx = tb.background.getContext('2d');
    ctx.strokeStyle = ROBOT_BLUE; ctx.lineWidth = 1.5;
    ctx.beginPath();
    const start = Math.max(0, from - 1);
    tb.trail.slice(start).forEach(([x, y], i) => { const [px, py] = toPixel(x, y); if (i) ctx.lineTo(px, py); else ctx.moveTo(px, py); });
    ctx.stroke();
  }

  function drawTb3() {
    const ctx = tb.ctx;
    ctx.drawImage(tb.background, 0, 0);
    ctx.fillStyle = SCAN_RED;
    for (const [x, y] of tb.scan) { const [px, py] = toPixel(x, y); ctx.fillRect(Math.round(px) - 2, Math.round(py) - 2, 4, 4); }
    if (!tb.pose) return;
    const [x, y, yaw] = tb.pose, b = tb.body, c = Math.cos(yaw), s = Math.sin(yaw);
    const corners = [[b.length / 2, b.width / 2], [-b.length / 2, b.width / 2], [-b.length / 2, -b.width / 2], [b.length / 2, -b.width / 2]]
      .map(([u, v]) => toPixel(x + (b.offset_x + u) * c - v * s, y + (b.offset_x + u) * s + v * c));
    ctx.fillStyle = 'rgba(30,90,200,0.35)'; ctx.strokeStyle = ROBOT_BLUE; ctx.lineWidth = 2;
    ctx.beginPath(); corners.forEach(([px, py], i) => (i ? ctx.lineTo(px, py) : ctx.moveTo(px, py))); ctx.closePath();
    ctx.fill(); ctx.stroke();
    const nose = b.offset_x + b.length / 2 + 0.05;
    const [ax, ay] = toPixel(x, y), [bx, by] = toPixel(x + nose * c, y + nose * s);
    ctx.beginPath(); ctx.moveTo(ax, ay); ctx.lineTo(bx, by); ctx.stroke();
  }

  let lastRecorded = null;
  function tb3Part(part) {
    $('tb3').hidden = !part.present;
    if (!part.present) { tb.world = null; tb.trail = []; tb.scan = []; tb.pose = null; return; }
    if (part.world) { tb.world = part.world; tb.body = part.body; tb.view = null; $('tb3-world').textContent = part.world.name + ', ' + part.body.model; }
    if (part.trail_reset) tb.trail = [];
    const from = tb.trail.length;
    for (const point of part.trail) tb.trail.push(point);
    stats.tb3TrailLength = tb.trail.length;
    if (part.scan) { tb.scan = part.scan; stats.scans++; }
    if (part.pose) {
      tb.pose = part.pose;
      const [x, y, yaw] = part.pose, [v, w] = part.speed;
      $('tb3-pose').textContent = `x ${x.toFixed(3)} m, y ${y.toFixed(3)} m, yaw ${(yaw * 180 / Math.PI).toFixed(1)}°`;
      $('tb3-speed').textContent = `${v.toFixed(2)} m/s, ${w.toFixed(2)} rad/s`;
      $('tb3-closest').textContent = part.closest === null ? 'nothing in range' : `${part.closest.toFixed(3)} m`;
    }
    if (!tb.world) return;
    if (!tb.view || (tb.pose && !wanted(tb.view, tb.pose[0], tb.pose[1]))) chooseView();
    else if (tb.trail.length > from) drawTrail(from);
    drawTb3();
    if (part.pose && !(lastRecorded && part.pose.every((v, i) => v === lastRecorded[i]))) {
      stats.tb3Poses++;
      recordDrawn('tb3', part.pose[0]);  // a new pose, not a scan beside the same pose
      lastRecorded = part.pose;
    }
  }

  // ---------------------------------------------------------------- frames
  // One frame (in order: a frame may wait for turtlesim's canvas image to decode).
  async function show(frame) {
    stats.frames++;
    if (frame.turtlesim) { stats.turtlesimFrames++; await turtlesimPart(frame.turtlesim); }
    if (frame.tb3) { stats.tb3Frames++; tb3Part(frame.tb3); }
    showWaiting();
  }

  // No source of frames any more: both parts go.
  function clear() { turtlesimPart({present: false}); tb3Part({present: false}); }

  return {show: show, clear: clear};
}());
