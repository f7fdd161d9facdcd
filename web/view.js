// The page of `plateball view`. Reads PLATEBALL_DATA (written by tools/view/view_data.cc):
//   t[n]                 sample times
//   x[2n], q[4n]         contact point and orientation A(t) as unit quaternions (w, x, y, z), the
//                        library's values at t[i]; between samples the orientation is the slerp
//                        on SO(3) (never Euler angles), the contact point linear
//   ghost {x, q, error}  the ghost ball on the planned path at the same times and the angle
//                        |log(A_ghost^T A)| (rad) computed by the library; absent without a path
//   planned[2m]          the planned path (polyline), impulses [{t, x, dv}], goal [2]
//   spread [{label, x}]  Monte Carlo: final contact points of the trials, per (strategy, scenario)
//   kind, title, facts [[label, value]], generator
//   rig                  a steer result's rig (optional): shapes and stroke for rig_layers.js, and
//                        check {passed, samples, margins [[limit, margin]], violations, active,
//                        blocking, constrained, objective} when the result carries its replay check
// World frame as the library's: the plates are z = 0 and z = 2, the ball (radius 1) centred at
// (x, y, 1).
(function () {
  "use strict";
  const D = PLATEBALL_DATA;
  const T = D.t;
  const n = T.length;
  const t0 = T[0];
  const t1 = T[n - 1];
  const $ = (id) => document.getElementById(id);

  // ------------------------------------------------------------ SO(3), double precision
  function quat(qs, i) { return [qs[4 * i], qs[4 * i + 1], qs[4 * i + 2], qs[4 * i + 3]]; }
  function slerp(a, b, u) {
    if (u === 0) return a.slice();
    if (u === 1) return b.slice();
    let d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const s = d < 0 ? -1 : 1;
    d = Math.abs(d);
    let wa, wb;
    if (d > 1 - 1e-12) {  // nearly equal: the linear blend, normalised below
      wa = 1 - u;
      wb = u;
    } else {
      const theta = Math.acos(d);
      const sin = Math.sin(theta);
      wa = Math.sin((1 - u) * theta) / sin;
      wb = Math.sin(u * theta) / sin;
    }
    const q = [0, 1, 2, 3].map((k) => wa * a[k] + s * wb * b[k]);
    const norm = Math.hypot(q[0], q[1], q[2], q[3]);
    return q.map((c) => c / norm);
  }
  function matrix(q) {  // rows of R(q), q = (w, x, y, z)
    const [w, x, y, z] = q;
    return [
      [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ];
  }
  // Largest i with T[i] <= t (0 before the start), and the fraction u towards i + 1.
  function locate(t) {
    if (!(t > t0)) return { i: 0, u: 0 };
    if (t >= t1) return { i: n - 1, u: 0 };
    let lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (T[mid] <= t) lo = mid; else hi = mid;
    }
    return { i: lo, u: (t - T[lo]) / (T[lo + 1] - T[lo]) };
  }
  function stateAt(xs, qs, at) {
    const { i, u } = at;
    const j = Math.min(i + 1, n - 1);
    return {
      x: [xs[2 * i] + u * (xs[2 * j] - xs[2 * i]), xs[2 * i + 1] + u * (xs[2 * j + 1] - xs[2 * i + 1])],
      q: slerp(quat(qs, i), quat(qs, j), u),
    };
  }

  // ------------------------------------------------------------ scene
  const host = $("scene");
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    $("message").textContent = "This page needs WebGL: " + e.message;
    return;
  }
  renderer.setPixelRatio(1);
  host.insertBefore(renderer.domElement, host.firstChild);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xfbfbf9);
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(-3, -5, 9);
  scene.add(sun);

  // Extent of everything drawn, on the plate.
  const box = new THREE.Box2();
  const addPoints = (a) => { for (let k = 0; k + 1 < a.length; k += 2) box.expandByPoint(new THREE.Vector2(a[k], a[k + 1])); };
  addPoints(D.x);
  addPoints(D.planned || []);
  for (const cell of D.spread) addPoints(cell.x);
  if (D.goal) addPoints(D.goal);
  const rig = D.rig ? PlateballRigLayers.build(D.rig) : null;
  if (rig) addPoints(rig.points.flat());
  box.expandByScalar(1.6);
  const centre = box.getCenter(new THREE.Vector2());
  const size = box.getSize(new THREE.Vector2());
  const extent = Math.max(size.x, size.y);

  // Lower plate: a light slab with a grid of spacing 1, 10, 100, ... so that it has at most
  // kMaxGridLines lines whatever the extent (a unit grid over a long simulation would need more
  // lines than an array can hold).
  const kMaxGridLines = 200;
  const gridStep = (size) => { let step = 1; while (size / step > kMaxGridLines && step < 1e30) step *= 10; return step; };
  const plateStep = gridStep(extent + 2);
  const plateSize = plateStep * Math.ceil((extent + 2) / plateStep);
  const lower = new THREE.Mesh(new THREE.PlaneGeometry(plateSize, plateSize),
    new THREE.MeshBasicMaterial({ color: 0xefede6 }));
  lower.position.set(centre.x, centre.y, -0.001);
  scene.add(lower);
  const grid = new THREE.GridHelper(plateSize, Math.round(plateSize / plateStep), 0xd6d3ca, 0xd6d3ca);
  grid.rotation.x = Math.PI / 2;
  grid.position.set(centre.x, centre.y, 0);
  scene.add(grid);

  // Upper plate at z = 2, translucent, its own grid so that its motion shows.
  const upper = new THREE.Group();
  const upperStep = gridStep(Math.max(5, 0.6 * extent));
  const upperSize = upperStep * Math.max(5, Math.ceil(0.6 * extent / upperStep));
  upper.add(new THREE.Mesh(new THREE.PlaneGeometry(upperSize, upperSize),
    new THREE.MeshBasicMaterial({ color: 0xd8c27a, transparent: true, opacity: 0.16, side: THREE.DoubleSide, depthWrite: false })));
  const upperGrid = new THREE.GridHelper(upperSize, Math.round(upperSize / upperStep), 0xa08a3a, 0xa08a3a);
  upperGrid.rotation.x = Math.PI / 2;
  upperGrid.material.transparent = true;
  upperGrid.material.opacity = 0.45;
  upper.add(upperGrid);
  scene.add(upper);
  const x0 = [D.x[0], D.x[1]];

  // The rig's limits: the plate's edge with the outside shaded, the obstacles, the clearance curves
  // dashed, and the stroke: the box of the upper plate's reference point on the upper plate's plane
  // (that point is marked with a cross on the upper plate) and the same limit for the contact point.
  const rigGroup = new THREE.Group();
  scene.add(rigGroup);
  const rigColours = { plate: 0x444444, outside: 0x77736a, obstacle: 0x8e2b2b, obstacleFill: 0xe8b4b4, stroke: 0x8a5a00 };
  const bandWidth = 0.004 * extent + 0.03;
  // A closed loop as a flat band of `width` (mitred corners), at height z.
  function band(loop, width, colour, z) {
    const m = loop.length;
    const a = new Float32Array(6 * m);
    for (let k = 0; k < m; ++k) {
      const p = loop[k], b = loop[(k + m - 1) % m], f = loop[(k + 1) % m];
      const n0 = [b[1] - p[1], p[0] - b[0]], n1 = [p[1] - f[1], f[0] - p[0]];
      const l0 = Math.hypot(n0[0], n0[1]) || 1, l1 = Math.hypot(n1[0], n1[1]) || 1;
      let nx = n0[0] / l0 + n1[0] / l1, ny = n0[1] / l0 + n1[1] / l1;
      const ln = Math.hypot(nx, ny) || 1;
      const miter = Math.min(3, 1 / Math.max(1e-3, (nx * n1[0] / l1 + ny * n1[1] / l1) / ln));
      nx = (nx / ln) * miter * width / 2;
      ny = (ny / ln) * miter * width / 2;
      a.set([p[0] + nx, p[1] + ny, z, p[0] - nx, p[1] - ny, z], 6 * k);
    }
    const index = new Uint32Array(6 * m);
    for (let k = 0; k < m; ++k) {
      const j = (k + 1) % m;
      index.set([2 * k, 2 * k + 1, 2 * j, 2 * k + 1, 2 * j + 1, 2 * j], 6 * k);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(a, 3));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    return new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: colour, side: THREE.DoubleSide }));
  }
  function dashed(polyline, colour, z) {
    const geometry = new THREE.BufferGeometry();
    const a = new Float32Array(3 * polyline.length);
    polyline.forEach((p, k) => a.set([p[0], p[1], z], 3 * k));
    geometry.setAttribute("position", new THREE.BufferAttribute(a, 3));
    const object = new THREE.Line(geometry, new THREE.LineDashedMaterial({ color: colour, dashSize: 0.008 * extent + 0.04, gapSize: 0.006 * extent + 0.03 }));
    object.computeLineDistances();
    return object;
  }
  const shapeOf = (loop) => new THREE.Shape(loop.map((p) => new THREE.Vector2(p[0], p[1])));
  let referenceMarker = null;
  if (rig) {
    if (rig.plate) {
      const outside = shapeOf([[centre.x - plateSize / 2, centre.y - plateSize / 2], [centre.x + plateSize / 2, centre.y - plateSize / 2],
        [centre.x + plateSize / 2, centre.y + plateSize / 2], [centre.x - plateSize / 2, centre.y + plateSize / 2]]);
      outside.holes.push(new THREE.Path(rig.plate.outline.map((p) => new THREE.Vector2(p[0], p[1]))));
      const shade = new THREE.Mesh(new THREE.ShapeGeometry(outside), new THREE.MeshBasicMaterial({
        color: rigColours.outside, transparent: true, opacity: 0.35, depthWrite: false }));
      shade.position.z = 0.0005;
      rigGroup.add(shade);
      rigGroup.add(band(rig.plate.outline, bandWidth, rigColours.plate, 0.001));
      for (const c of rig.plate.clearance) rigGroup.add(dashed(c, rigColours.plate, 0.0015));
    }
    for (const o of rig.obstacles) {
      const fill = new THREE.Mesh(new THREE.ShapeGeometry(shapeOf(o.outline)), new THREE.MeshBasicMaterial({ color: rigColours.obstacleFill }));
      fill.position.z = 0.0008;
      rigGroup.add(fill);
      rigGroup.add(band(o.outline, bandWidth, rigColours.obstacle, 0.001));
      for (const c of o.clearance) rigGroup.add(dashed(c, rigColours.obstacle, 0.0015));
    }
    if (rig.stroke) {
      rigGroup.add(band(rig.stroke.upper, bandWidth, rigColours.stroke, 2.002));
      rigGroup.add(dashed(rig.stroke.contact.concat([rig.stroke.contact[0]]), rigColours.stroke, 0.002));
      // The upper plate's reference point (above x0 at the start): a cross that moves with it.
      referenceMarker = new THREE.Group();
      const arm = 0.03 * extent + 0.15;
      for (const [w, h] of [[2 * arm, bandWidth], [bandWidth, 2 * arm]]) {
        const bar = new THREE.Mesh(new THREE.PlaneGeometry(w, h), new THREE.MeshBasicMaterial({ color: rigColours.stroke, side: THREE.DoubleSide }));
        bar.position.z = 0.003;
        referenceMarker.add(bar);
      }
      upper.add(referenceMarker);
    }
  }

  // The ball: poles on its body axis e3 (red: +e3, the symmetry axis z = A e3; blue: -e3),
  // eight coloured octants and a dark equator, so that every rotation shows.
  function ballTexture() {
    const c = document.createElement("canvas");
    c.width = 512;
    c.height = 256;
    const g = c.getContext("2d");
    const colours = ["#f2f2ee", "#f0a040", "#f2f2ee", "#4a8fd8"];
    for (let k = 0; k < 4; ++k) {
      g.fillStyle = colours[k];
      g.fillRect(k * 128, 0, 128, 128);
      g.fillStyle = colours[(k + 1) % 4];
      g.fillRect(k * 128, 128, 128, 128);
    }
    g.fillStyle = "#d04040";
    g.fillRect(0, 0, 512, 22);
    g.fillStyle = "#3050a0";
    g.fillRect(0, 234, 512, 22);
    g.fillStyle = "#333";
    g.fillRect(0, 125, 512, 6);
    g.fillRect(0, 0, 4, 256);
    const tex = new THREE.CanvasTexture(c);
    tex.colorSpace = THREE.SRGBColorSpace;
    return tex;
  }
  const sphere = new THREE.SphereGeometry(1, 64, 40);
  sphere.rotateX(Math.PI / 2);  // three's poles are on y; the body's symmetry axis is e3
  const texture = ballTexture();
  const ball = new THREE.Mesh(sphere, new THREE.MeshStandardMaterial({ map: texture, roughness: 0.6 }));
  scene.add(ball);
  const ghost = new THREE.Mesh(sphere, new THREE.MeshBasicMaterial({
    map: texture, color: 0x9ab7e0, transparent: true, opacity: 0.33, depthWrite: false }));
  ghost.visible = !!D.ghost;
  scene.add(ghost);

  // Paths: planned dashed, contact path traced (draw range grows with time).
  const lift = 0.004;
  function line(points, material) {
    const geometry = new THREE.BufferGeometry();
    const a = new Float32Array((points.length / 2) * 3);
    for (let k = 0; 2 * k + 1 < points.length; ++k) a.set([points[2 * k], points[2 * k + 1], lift], 3 * k);
    geometry.setAttribute("position", new THREE.BufferAttribute(a, 3));
    const object = new THREE.Line(geometry, material);
    scene.add(object);
    return object;
  }
  const planned = D.planned && D.planned.length >= 4
    ? line(D.planned, new THREE.LineDashedMaterial({ color: 0x1f5fbf, dashSize: 0.012 * extent, gapSize: 0.009 * extent }))
    : null;
  if (planned) planned.computeLineDistances();
  if (planned) planned.position.z = 0.006;
  // The contact path as a flat ribbon (WebGL lines are one pixel wide), drawn up to the current
  // sample: segment i is the indices 6i ... 6i + 5.
  function ribbon(points, width, material) {
    const m = points.length / 2;
    const a = new Float32Array(6 * m);
    for (let k = 0; k < m; ++k) {
      const kb = Math.max(0, k - 1), kf = Math.min(m - 1, k + 1);
      let dx = points[2 * kf] - points[2 * kb], dy = points[2 * kf + 1] - points[2 * kb + 1];
      const len = Math.hypot(dx, dy) || 1;
      dx = (-dy / len) * width / 2;
      dy = ((points[2 * kf] - points[2 * kb]) / len) * width / 2;
      a.set([points[2 * k] + dx, points[2 * k + 1] + dy, lift, points[2 * k] - dx, points[2 * k + 1] - dy, lift], 6 * k);
    }
    const index = new Uint32Array(6 * Math.max(0, m - 1));
    for (let k = 0; k + 1 < m; ++k) index.set([2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 1, 2 * k + 3, 2 * k + 2], 6 * k);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(a, 3));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    const object = new THREE.Mesh(geometry, material);
    scene.add(object);
    return object;
  }
  const trace = ribbon(D.x, 0.006 * extent + 0.02, new THREE.MeshBasicMaterial({ color: 0xc0392b, side: THREE.DoubleSide }));

  // Impulses: a dot at the point, an arrow along the upper plate's velocity change.
  const arrows = new THREE.Group();
  scene.add(arrows);
  let dvMax = 0;
  for (const imp of D.impulses) dvMax = Math.max(dvMax, Math.hypot(imp.dv[0], imp.dv[1]));
  const arrowItems = D.impulses.map((imp) => {
    const dot = new THREE.Mesh(new THREE.CircleGeometry(0.003 * extent + 0.015, 16), new THREE.MeshBasicMaterial({ color: 0x111111 }));
    dot.position.set(imp.x[0], imp.x[1], 2 * lift);
    arrows.add(dot);
    const len = Math.hypot(imp.dv[0], imp.dv[1]);
    let arrow = null;
    if (len > 0 && dvMax > 0) {
      const l = 0.1 * extent * Math.sqrt(len / dvMax) + 0.05;
      arrow = new THREE.ArrowHelper(new THREE.Vector3(imp.dv[0] / len, imp.dv[1] / len, 0),
        new THREE.Vector3(imp.x[0], imp.x[1], 3 * lift), l, 0x2a9d4b, 0.3 * l, 0.18 * l);
      arrows.add(arrow);
    }
    return { t: imp.t, arrow };
  });
  if (D.goal) {
    const ring = new THREE.Mesh(new THREE.RingGeometry(0.18, 0.26, 32), new THREE.MeshBasicMaterial({ color: 0x2e8b57 }));
    ring.position.set(D.goal[0], D.goal[1], 2 * lift);
    scene.add(ring);
  }

  const spreadColours = ["#7b3fa0", "#e07b00", "#1b9e77", "#d62728", "#17becf", "#8c564b"];
  D.spread.forEach((cell, c) => {
    const g = new THREE.BufferGeometry();
    const a = new Float32Array((cell.x.length / 2) * 3);
    for (let k = 0; 2 * k + 1 < cell.x.length; ++k) a.set([cell.x[2 * k], cell.x[2 * k + 1], 3 * lift], 3 * k);
    g.setAttribute("position", new THREE.BufferAttribute(a, 3));
    scene.add(new THREE.Points(g, new THREE.PointsMaterial({ color: spreadColours[c % 6], size: 4, sizeAttenuation: false })));
  });

  // Camera: a three-quarter view of the whole extent; drag turns it about the centre, wheel zooms.
  const camera = new THREE.PerspectiveCamera(40, 1, 0.05, 1000);
  camera.up.set(0, 0, 1);
  const orbit = { azimuth: -2.1, elevation: 0.85, distance: 1.5 * extent + 5 };
  function placeCamera() {
    const c = Math.cos(orbit.elevation);
    camera.position.set(centre.x + orbit.distance * c * Math.cos(orbit.azimuth),
      centre.y + orbit.distance * c * Math.sin(orbit.azimuth), 1 + orbit.distance * Math.sin(orbit.elevation));
    camera.lookAt(centre.x, centre.y, 0.5);
  }
  placeCamera();
  let drag = null;
  renderer.domElement.addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY }; });
  window.addEventListener("pointerup", () => { drag = null; });
  window.addEventListener("pointermove", (e) => {
    if (!drag) return;
    orbit.azimuth -= 0.008 * (e.clientX - drag.x);
    orbit.elevation = Math.min(1.5, Math.max(0.08, orbit.elevation + 0.008 * (e.clientY - drag.y)));
    drag = { x: e.clientX, y: e.clientY };
    placeCamera();
    requestRender();
  });
  renderer.domElement.addEventListener("wheel", (e) => {
    e.preventDefault();
    orbit.distance = Math.min(20 * extent + 20, Math.max(2, orbit.distance * Math.exp(0.001 * e.deltaY)));
    placeCamera();
    requestRender();
  }, { passive: false });

  // ------------------------------------------------------------ charts (2-D canvases)
  function axes(g, w, h, pad, xr, yr, xlabel, ylabel) {
    g.clearRect(0, 0, w, h);
    g.strokeStyle = "#999";
    g.lineWidth = 1.5;
    g.strokeRect(pad.l, pad.t, w - pad.l - pad.r, h - pad.t - pad.b);
    g.fillStyle = "#444";
    g.font = "20px system-ui, sans-serif";
    g.textAlign = "center";
    g.fillText(xlabel, (w + pad.l - pad.r) / 2, h - 6);
    g.textAlign = "left";
    g.fillText(xr[0].toPrecision(3), pad.l, h - pad.b + 22);
    g.textAlign = "right";
    g.fillText(xr[1].toPrecision(3), w - pad.r, h - pad.b + 22);
    g.textAlign = "right";
    g.fillText(yr[1].toPrecision(3), pad.l - 4, pad.t + 14);
    g.fillText(yr[0].toPrecision(3), pad.l - 4, h - pad.b);
    g.save();
    g.translate(16, (h + pad.t - pad.b) / 2);
    g.rotate(-Math.PI / 2);
    g.textAlign = "center";
    g.fillText(ylabel, 0, 0);
    g.restore();
  }
  const chart = $("chart");
  const chartPad = { l: 92, r: 16, t: 12, b: 48 };
  let chartImage = null;
  let errMax = 0;
  function drawChartBase() {
    const g = chart.getContext("2d");
    if (!D.ghost) {
      g.clearRect(0, 0, chart.width, chart.height);
      chart.hidden = true;
      $("chart-note").textContent = "No planned path in this result (a free motion): no orientation error to show.";
      return;
    }
    for (const e of D.ghost.error) errMax = Math.max(errMax, e);
    errMax = errMax > 0 ? errMax * 1.08 : 1;
    axes(g, chart.width, chart.height, chartPad, [t0, t1], [0, errMax], "time t", "angle(A, A_ghost) (rad)");
    const w = chart.width - chartPad.l - chartPad.r, h = chart.height - chartPad.t - chartPad.b;
    g.strokeStyle = "#c0392b";
    g.lineWidth = 2;
    g.beginPath();
    const step = Math.max(1, Math.floor(n / (2 * w)));
    for (let i = 0; i < n; i += step) {
      const px = chartPad.l + (w * (T[i] - t0)) / (t1 - t0 || 1);
      const py = chartPad.t + h * (1 - D.ghost.error[i] / errMax);
      if (i === 0) g.moveTo(px, py); else g.lineTo(px, py);
    }
    g.stroke();
    chartImage = g.getImageData(0, 0, chart.width, chart.height);
    $("chart-note").textContent = "Geodesic angle between the ball's A(t) and the ghost's (rolling along the planned path, "
      + "passing each planned point when the ball does); final " + D.ghost.error[n - 1].toExponential(3) + " rad.";
  }
  function drawChartCursor(t) {
    if (!chartImage) return;
    const g = chart.getContext("2d");
    g.putImageData(chartImage, 0, 0);
    const w = chart.width - chartPad.l - chartPad.r;
    const px = chartPad.l + (w * (t - t0)) / (t1 - t0 || 1);
    g.strokeStyle = "#1f5fbf";
    g.lineWidth = 1.5;
    g.beginPath();
    g.moveTo(px, chartPad.t);
    g.lineTo(px, chart.height - chartPad.b);
    g.stroke();
  }

  // The final contact points around the goal, one colour per (strategy, scenario), equal scales.
  function drawSpread() {
    if (!D.spread.length) return;
    $("spread-section").hidden = false;
    const c = $("spread"), g = c.getContext("2d");
    const b = new THREE.Box2();
    for (const cell of D.spread) for (let k = 0; k + 1 < cell.x.length; k += 2) b.expandByPoint(new THREE.Vector2(cell.x[k], cell.x[k + 1]));
    if (D.goal) b.expandByPoint(new THREE.Vector2(D.goal[0], D.goal[1]));
    const pad = { l: 92, r: 16, t: 12, b: 48 };
    const w = c.width - pad.l - pad.r, h = c.height - pad.t - pad.b;
    const sz = b.getSize(new THREE.Vector2()), mid = b.getCenter(new THREE.Vector2());
    const scale = Math.min(w / Math.max(sz.x, 1e-15), h / Math.max(sz.y, 1e-15)) * 0.9;
    const px = (x) => pad.l + w / 2 + (x - mid.x) * scale, py = (y) => pad.t + h / 2 - (y - mid.y) * scale;
    axes(g, c.width, c.height, pad, [mid.x - w / 2 / scale, mid.x + w / 2 / scale], [mid.y - h / 2 / scale, mid.y + h / 2 / scale], "x", "y");
    D.spread.forEach((cell, i) => {
      g.fillStyle = spreadColours[i % 6];
      for (let k = 0; k + 1 < cell.x.length; k += 2) g.fillRect(px(cell.x[k]) - 2.5, py(cell.x[k + 1]) - 2.5, 5, 5);
      const li = document.createElement("li");
      li.innerHTML = '<span class="dot"></span>';
      li.firstChild.style.background = spreadColours[i % 6];
      li.append(cell.label + " (" + cell.x.length / 2 + " trials)");
      $("spread-legend").append(li);
    });
    if (D.goal) {
      g.strokeStyle = "#2e8b57";
      g.lineWidth = 3;
      g.beginPath();
      g.arc(px(D.goal[0]), py(D.goal[1]), 9, 0, 2 * Math.PI);
      g.stroke();
    }
  }

  // ------------------------------------------------------------ state, controls
  let time = t0;
  let current = stateAt(D.x, D.q, locate(t0));
  let playing = false;
  let frames = 0;
  let renderPending = false;
  const slider = $("time");
  slider.min = String(t0);
  slider.max = String(t1);
  slider.value = String(t0);

  function seek(t) {
    time = Math.min(t1, Math.max(t0, t));
    const at = locate(time);
    current = stateAt(D.x, D.q, at);
    ball.position.set(current.x[0], current.x[1], 1);
    ball.quaternion.set(current.q[1], current.q[2], current.q[3], current.q[0]);
    upper.position.set(x0[0] + 2 * (current.x[0] - x0[0]), x0[1] + 2 * (current.x[1] - x0[1]), 2);
    trace.geometry.setDrawRange(0, 6 * at.i);
    if (D.ghost) {
      const g = stateAt(D.ghost.x, D.ghost.q, at);
      ghost.position.set(g.x[0], g.x[1], 1);
      ghost.quaternion.set(g.q[1], g.q[2], g.q[3], g.q[0]);
    }
    for (const a of arrowItems) {
      if (!a.arrow) continue;
      const past = time >= a.t;
      a.arrow.line.material.opacity = past ? 1 : 0.3;
      a.arrow.line.material.transparent = !past;
      a.arrow.cone.material.opacity = past ? 1 : 0.3;
      a.arrow.cone.material.transparent = !past;
    }
    $("clock").textContent = "t = " + time.toFixed(4) + " / " + t1.toFixed(4);
    drawChartCursor(time);
    requestRender();
  }
  slider.addEventListener("input", () => seek(parseFloat(slider.value)));
  const play = $("play");
  play.addEventListener("click", () => {
    playing = !playing;
    if (playing && time >= t1) seek(t0);
    play.textContent = playing ? "Pause" : "Play";
    last = null;
    requestRender();
  });
  const layers = { "show-rig": rig ? rigGroup : null, "show-upper": upper, "show-trace": trace, "show-ghost": ghost, "show-planned": planned, "show-arrows": arrows };
  for (const [id, object] of Object.entries(layers)) {
    $(id).addEventListener("change", (e) => {
      if (object) object.visible = e.target.checked && (object !== ghost || !!D.ghost);
      if (object === rigGroup && referenceMarker) referenceMarker.visible = e.target.checked;
      requestRender();
    });
  }
  // Base rate: the whole motion in about 20 s at 1x.
  const baseRate = (t1 - t0) / 20;
  let last = null;
  function resize() {
    const w = host.clientWidth, h = host.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
    requestRender();
  }
  function frame(now) {
    renderPending = false;
    if (playing) {
      if (last !== null) {
        const next = time + ((now - last) / 1000) * baseRate * parseFloat($("speed").value);
        seek(next);
        slider.value = String(time);
        if (time >= t1) {
          playing = false;
          play.textContent = "Play";
        }
      }
      last = now;
    }
    renderer.render(scene, camera);
    ++frames;
    if (playing) requestRender();
  }
  function requestRender() {
    if (renderPending) return;
    renderPending = true;
    requestAnimationFrame(frame);
  }
  window.addEventListener("resize", resize);

  // ------------------------------------------------------------ panel
  $("title").textContent = D.title;
  document.title = D.title;
  const facts = $("facts");
  const addFact = (label, value) => {
    const dt = document.createElement("dt"), dd = document.createElement("dd");
    dt.textContent = label;
    dd.textContent = value;
    facts.append(dt, dd);
  };
  for (const [label, value] of D.facts) addFact(label, value);
  addFact("samples", n + " (A(t) from the library; slerp between them)");
  addFact("re-simulation", "matches the result's orientations to " + D.resimulation_mismatch.toExponential(1));
  if (D.impulses.length) addFact("impulses", String(D.impulses.length));
  $("generator").textContent = "Written by " + D.generator + ".";
  if (rig) showRig();

  // The rig's legend entries and the verdict of the result's independent replay check. Every
  // string of the data goes in as text (textContent, append), never as markup.
  function legendItem(text, style) {
    const li = document.createElement("li");
    const swatch = document.createElement("span");
    swatch.className = "swatch";
    Object.assign(swatch.style, style);
    li.append(swatch, text);
    $("legend").append(li);
  }
  function showRig() {
    $("show-rig-label").hidden = !(rig.plate || rig.obstacles.length || rig.stroke);
    const hex = (c) => "#" + c.toString(16).padStart(6, "0");
    const c = D.rig.clearance || 0;
    if (rig.plate) {
      legendItem("plate edge: the contact point stays inside", { borderColor: hex(rigColours.plate) });
      legendItem("outside the plate", { height: "10px", borderTop: "0", background: hex(rigColours.outside), opacity: "0.6" });
    }
    if (rig.obstacles.length)
      legendItem("obstacles: the contact point stays outside", { height: "8px", borderTopColor: hex(rigColours.obstacle), background: hex(rigColours.obstacleFill) });
    if (c > 0 && (rig.plate || rig.obstacles.length)) {
      const skipped = [rig.plate, ...rig.obstacles].filter((l) => l && l.clearanceSkipped).length;
      legendItem("clearance " + c.toPrecision(3) + " r from the plate edge and the obstacles"
        + (skipped ? " (not drawn for " + skipped + " large polygons: over the page's work budget)" : ""),
        { borderColor: "#555", borderTopStyle: "dashed" });
    }
    if (rig.stroke) {
      legendItem("upper plate's stroke (at z = 2): its reference point (cross, above x0 at the start) stays in x0 \u00b1 ("
        + rig.stroke.half.map((v) => v.toPrecision(3)).join(", ") + ")", { borderColor: hex(rigColours.stroke) });
      legendItem("the same stroke for the contact point: x0 \u00b1 s / 2 (the upper plate moves 2 (x - x0))",
        { borderColor: hex(rigColours.stroke), borderTopStyle: "dashed" });
    }
    const section = $("rig-section");
    section.hidden = false;
    const k = D.rig.check;
    const verdict = $("rig-verdict");
    if (!k) {
      verdict.textContent = "This result carries no rig check: the limits are drawn, not checked.";
      return;
    }
    verdict.textContent = (k.passed ? "Limits met in the replay check: " : "Limits NOT met in the replay check: ") + k.samples
      + " contact points and every impulse and time of an independent replay checked (whether the goal is reached: the report).";
    verdict.className = k.passed ? "pass" : "fail";
    const table = $("rig-margins");
    for (const [name, margin] of k.margins) {
      const row = table.insertRow();
      row.insertCell().textContent = name;
      const cell = row.insertCell();
      cell.textContent = margin.toPrecision(4);
      cell.className = margin >= 0 ? "pass" : "fail";
    }
    const rigFact = (label, value) => {
      const dt = document.createElement("dt"), dd = document.createElement("dd");
      dt.textContent = label;
      dd.textContent = value;
      $("rig-facts").append(dt, dd);
    };
    rigFact("objective", k.objective);
    rigFact("constrained", k.constrained ? "yes: the limits cut the free optimum" : "no: the free optimum meets them");
    rigFact("active", k.active.length ? k.active.join(", ") : "none");
    if (k.blocking.length) rigFact("blocking", k.blocking.join(", "));
    for (const v of k.violations) rigFact("violation", v);
  }

  drawChartBase();
  drawSpread();
  resize();
  seek(t0);

  // ------------------------------------------------------------ read-only hook for the tests
  const projected = (v) => {
    const p = v.clone().project(camera);
    const r = renderer.domElement.getBoundingClientRect();
    return [r.left + ((p.x + 1) / 2) * r.width, r.top + ((1 - p.y) / 2) * r.height];
  };
  window.plateballView = Object.freeze({
    kind: D.kind,
    sampleCount: () => n,
    range: () => [t0, t1],
    time: () => time,
    playing: () => playing,
    frames: () => frames,
    orientation: () => matrix(current.q),
    // The angle between the ball and the ghost now (linear between samples), or null.
    orientationError: () => {
      if (!D.ghost) return null;
      const { i, u } = locate(time);
      const j = Math.min(i + 1, n - 1);
      return D.ghost.error[i] + u * (D.ghost.error[j] - D.ghost.error[i]);
    },
    // The times of the sample at fraction u of the samples and of the next one.
    sampleTimes: (u) => { const i = Math.min(n - 2, Math.floor(u * (n - 1))); return [T[i], T[i + 1]]; },
    contactPoint: () => current.x.slice(),
    spread: () => D.spread.map((cell) => ({ label: cell.label, x: cell.x.slice() })),
    goal: () => (D.goal ? D.goal.slice() : null),
    // The rig's layers as drawn (rig_layers.js), or null.
    rigLayers: () => (rig ? JSON.parse(JSON.stringify(rig)) : null),
    // Lines of the lower plate's grid (two vertices each).
    gridLines: () => grid.geometry.attributes.position.count / 2,
    // The ball's bounding box on the screen (CSS pixels): the projections of its bounding cube.
    ballBox: () => {
      const xs = [], ys = [];
      for (const dx of [-1, 1]) for (const dy of [-1, 1]) for (const dz of [0, 2]) {
        const [px, py] = projected(new THREE.Vector3(current.x[0] + dx, current.x[1] + dy, dz));
        xs.push(px);
        ys.push(py);
      }
      return { x0: Math.min(...xs), y0: Math.min(...ys), x1: Math.max(...xs), y1: Math.max(...ys) };
    },
  });
})();
