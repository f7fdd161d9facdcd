// The geometry of a rig's limits on the plates (plain numbers, no three.js), built from the page's
// `rig` object (tools/view/view_data.cc RigToJson):
//   plate {type: "disk", center, radius} | {type: "polygon", vertices [[x, y]]}   (optional)
//   obstacles [same shapes], clearance, stroke [s_x, s_y] (optional), x0 [2]
// Lengths in ball radii, on the lower plate's plane (z = 0) unless said otherwise. The contact
// point must stay `clearance` inside the plate and outside every obstacle (rig_limits.h), so the
// clearance curves are the level sets {signed distance to the shape's edge = clearance}. The
// upper plate moves at twice the ball centre's velocity: a point fixed on it that starts above x0
// is at x0 + 2 (x - x0), and the stroke |2 (x - x0)_i| <= s_i keeps it in the box x0 +- s (drawn
// on the upper plate's plane z = 2); the same limit keeps the contact point in x0 +- s / 2.
// Loaded before view.js in the page, and by web/test/rig_layers_test.mjs in node.
const PlateballRigLayers = (function () {
  "use strict";
  const kDiskSegments = 256;  // a drawn circle's chords: 1 - cos(pi / 256) = 7.5e-5 of the radius inside

  function circle(center, radius) {
    const points = [];
    for (let k = 0; k < kDiskSegments; ++k) {
      const a = (2 * Math.PI * k) / kDiskSegments;
      points.push([center[0] + radius * Math.cos(a), center[1] + radius * Math.sin(a)]);
    }
    return points;
  }

  const closed = (loop) => loop.concat([loop[0]]);

  // ------------------------------------------------------------ polygons
  function signedArea(v) {
    let a = 0;
    for (let i = 0; i < v.length; ++i) {
      const p = v[i], q = v[(i + 1) % v.length];
      a += p[0] * q[1] - q[0] * p[1];
    }
    return a / 2;
  }
  function segmentDistance(p, a, b) {
    const dx = b[0] - a[0], dy = b[1] - a[1];
    const len2 = dx * dx + dy * dy;
    const u = len2 > 0 ? Math.min(1, Math.max(0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2)) : 0;
    return Math.hypot(p[0] - a[0] - u * dx, p[1] - a[1] - u * dy);
  }
  // Distance to the polygon's edge, and whether p is inside (crossing number).
  function edgeDistance(v, p) {
    let d = Infinity;
    for (let i = 0; i < v.length; ++i) d = Math.min(d, segmentDistance(p, v[i], v[(i + 1) % v.length]));
    return d;
  }
  function inside(v, p) {
    let c = false;
    for (let i = 0, j = v.length - 1; i < v.length; j = i++) {
      if ((v[i][1] > p[1]) !== (v[j][1] > p[1]) &&
          p[0] < ((v[j][0] - v[i][0]) * (p[1] - v[i][1])) / (v[j][1] - v[i][1]) + v[i][0]) c = !c;
    }
    return c;
  }

  // The curve at distance d from the polygon's edge on one side (inward: true for the plate,
  // false for an obstacle), as polylines. It is made of the edges shifted by d along their normal
  // and arcs of radius d about the vertices; each piece is kept where no other part of the edge is
  // nearer than d (there it is the level set; elsewhere, at reflex corners, another edge is
  // nearer), the ends of the kept runs found by bisection.
  // `budget` {left}: distance evaluations still allowed (each costs one pass over the edges); a
  // polygon whose curve would take more gets none (null), so that a rig of many large polygons
  // cannot stall the page.
  function polygonOffset(v, d, inward, budget = { left: Infinity }) {
    const n = v.length;
    const orient = signedArea(v) > 0 ? 1 : -1;  // +1 counter-clockwise
    const side = inward ? -1 : 1;
    const normal = (i) => {  // unit normal of edge i (v[i] -> v[i+1]) towards the chosen side
      const a = v[i], b = v[(i + 1) % n];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      return [(side * orient * (b[1] - a[1])) / len, (-side * orient * (b[0] - a[0])) / len];
    };
    // Rounding of the distances (a few ulps of the coordinates), so that the shifted edges count as
    // the level set they are; a trimmed end found by bisection is this close to it.
    const scale = Math.max(1, d, ...v.map((p) => Math.max(Math.abs(p[0]), Math.abs(p[1]))));
    const tolerance = 1e-12 * scale;
    const keep = (p) => edgeDistance(v, p) >= d - tolerance && inside(v, p) === inward;
    const pieces = [];  // parametric pieces u in [0, 1] -> point, with a sample count
    let perimeter = 0;
    for (let i = 0; i < n; ++i) {
      const a = v[i], b = v[(i + 1) % n], m = normal(i);
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      perimeter += len;
      pieces.push({
        at: (u) => [a[0] + u * (b[0] - a[0]) + d * m[0], a[1] + u * (b[1] - a[1]) + d * m[1]],
        length: len,
      });
    }
    for (let i = 0; i < n; ++i) {
      const c = v[(i + 1) % n], m0 = normal(i), m1 = normal((i + 1) % n);
      const a0 = Math.atan2(m0[1], m0[0]);
      let sweep = Math.atan2(m1[1], m1[0]) - a0;
      while (sweep > Math.PI) sweep -= 2 * Math.PI;
      while (sweep < -Math.PI) sweep += 2 * Math.PI;
      if (sweep === 0) continue;
      pieces.push({
        at: (u) => [c[0] + d * Math.cos(a0 + u * sweep), c[1] + d * Math.sin(a0 + u * sweep)],
        length: Math.abs(sweep) * d,
      });
    }
    const step = Math.min(d, perimeter / n) / 8;  // samples finer than the features
    const samples = (piece) => Math.max(8, Math.min(2048, Math.ceil(piece.length / step)));
    const cost = n * pieces.reduce((sum, piece) => sum + samples(piece) + 1, 0);
    if (cost > budget.left) return null;
    budget.left -= cost;
    const curves = [];
    for (const piece of pieces) {
      const m = samples(piece);
      let run = null;
      let prevU = 0, prevKept = false;
      for (let k = 0; k <= m; ++k) {
        const u = k / m;
        const p = piece.at(u);
        const kept = keep(p);
        if (k > 0 && kept !== prevKept) {  // the run's end between prevU and u
          let lo = prevU, hi = u;
          for (let b = 0; b < 50; ++b) {
            const mid = (lo + hi) / 2;
            if (keep(piece.at(mid)) === prevKept) lo = mid; else hi = mid;
          }
          const edge = piece.at(prevKept ? lo : hi);
          if (prevKept) {
            run.push(edge);
            curves.push(run);
            run = null;
          } else {
            run = [edge];
          }
        }
        if (kept) {
          if (!run) run = [];
          run.push(p);
        }
        prevU = u;
        prevKept = kept;
      }
      if (run && run.length >= 2) curves.push(run);
    }
    return curves;
  }

  // ------------------------------------------------------------ shapes
  // The outline of a shape (a closed loop, the first point not repeated) and the clearance curves
  // (polylines; none for clearance 0 or an empty inner region).
  function shapeLayer(shape, clearance, inward, budget) {
    if (shape.type === "disk") {
      const r = inward ? shape.radius - clearance : shape.radius + clearance;
      return {
        type: "disk", center: shape.center.slice(), radius: shape.radius,
        outline: circle(shape.center, shape.radius),
        clearance: clearance > 0 && r > 0 ? [closed(circle(shape.center, r))] : [],
      };
    }
    const vertices = shape.vertices.map((p) => p.slice());
    const curves = clearance > 0 ? polygonOffset(vertices, clearance, inward, budget) : [];
    return {
      type: "polygon", vertices,
      outline: vertices.map((p) => p.slice()),
      clearance: curves || [],
      clearanceSkipped: curves === null,  // over the work budget: the outline only
    };
  }

  // The axis-aligned box c +- h as its four corners, counter-clockwise from (-, -).
  function box(c, h) {
    return [[c[0] - h[0], c[1] - h[1]], [c[0] + h[0], c[1] - h[1]], [c[0] + h[0], c[1] + h[1]], [c[0] - h[0], c[1] + h[1]]];
  }

  // Point-to-edge distances for all clearance curves of a page: 10^7, about a second of script (a
  // 1000-gon's curve takes 1.8e7; the largest rig a problem file may hold, 1000 polygons of 1000
  // vertices, would take 10^10).
  const kClearanceBudget = 1e7;

  function build(rig, budget = { left: kClearanceBudget }) {
    const clearance = rig.clearance || 0;
    const layers = {
      plate: rig.plate ? shapeLayer(rig.plate, clearance, true, budget) : null,
      obstacles: (rig.obstacles || []).map((o) => shapeLayer(o, clearance, false, budget)),
      stroke: null,
      points: [],  // every point drawn, for the view's extent
    };
    if (rig.stroke) {
      layers.stroke = {
        half: rig.stroke.slice(),
        origin: rig.x0.slice(),
        upper: box(rig.x0, rig.stroke),  // where the upper plate's reference point may go (z = 2)
        contact: box(rig.x0, [rig.stroke[0] / 2, rig.stroke[1] / 2]),  // the same limit for x (z = 0)
      };
    }
    const add = (list) => { for (const p of list) layers.points.push(p); };
    if (layers.plate) add(layers.plate.outline);
    for (const o of layers.obstacles) {
      add(o.outline);
      for (const c of o.clearance) add(c);
    }
    if (layers.stroke) add(layers.stroke.upper);
    return layers;
  }

  return Object.freeze({ build, polygonOffset, edgeDistance, inside, kDiskSegments, kClearanceBudget });
})();
if (typeof module !== "undefined" && module.exports) module.exports = PlateballRigLayers;
