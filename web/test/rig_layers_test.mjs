// Node tests of web/rig_layers.js, the geometry `plateball view` draws for a rig (ctest
// view.rig_layers; needs only node): shapes, clearance curves and the stroke boxes built from a rig
// object, checked against closed forms (circle radii, a square's and an L-shape's distance
// functions, Steiner's formula for the length of a convex set's parallel curve) and against the
// stroke limit |2 (x - x0)_i| <= s_i of rig_limits.h.
//   node web/test/rig_layers_test.mjs
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(import.meta.url);
const Rig = require(path.join(here, "..", "rig_layers.js"));

let failures = 0;
function check(ok, name, detail = "") {
  console.log((ok ? "ok - " : "not ok - ") + name + (detail ? ": " + detail : ""));
  if (!ok) ++failures;
}

// Coordinates are built from a few operations on the inputs: exact to a few ulps.
const kExact = 1e-12;
// A drawn arc is a polyline; the bisected ends of a trimmed piece lie on the level set to the
// bisection's 2^-50 of a piece: both far below a pixel.
const kOnCurve = 1e-9;
// The length of a polyline through points of an arc of radius d with chords of angle a is short by
// about a^2 / 24 of the arc; the finest sampling (a step of d / 8) is short by 1/1536 of each arc.
const kLengthRelative = 2e-3;

const length = (curves) => curves.reduce((sum, c) => {
  for (let k = 1; k < c.length; ++k) sum += Math.hypot(c[k][0] - c[k - 1][0], c[k][1] - c[k - 1][1]);
  return sum;
}, 0);
const maxOver = (curves, f) => Math.max(...curves.flat().map(f));

// ------------------------------------------------------------ disks
{
  const rig = { plate: { type: "disk", center: [1.5, 1.5], radius: 3 }, clearance: 0.05,
    obstacles: [{ type: "disk", center: [0, 1.45], radius: 0.25 }], x0: [0, 0] };
  const L = Rig.build(rig);
  const radius = (c) => (p) => Math.hypot(p[0] - c[0], p[1] - c[1]);
  const outlineError = maxOver([L.plate.outline], (p) => Math.abs(radius([1.5, 1.5])(p) - 3));
  const ringError = maxOver(L.plate.clearance, (p) => Math.abs(radius([1.5, 1.5])(p) - 2.95));
  const obstacleError = maxOver(L.obstacles[0].clearance, (p) => Math.abs(radius([0, 1.45])(p) - 0.30));
  const closedRing = L.plate.clearance.length === 1 &&
    Math.hypot(L.plate.clearance[0][0][0] - L.plate.clearance[0].at(-1)[0], L.plate.clearance[0][0][1] - L.plate.clearance[0].at(-1)[1]) === 0;
  check(L.plate.outline.length === Rig.kDiskSegments && outlineError < kExact && ringError < kExact && obstacleError < kExact && closedRing,
    "disk plate and obstacle: the outline on the radius, clearance rings at radius - c inside the plate and + c around the obstacle",
    `${L.plate.outline.length} vertices, errors ${outlineError.toExponential(1)}, ${ringError.toExponential(1)}, ${obstacleError.toExponential(1)}`);
  const none = Rig.build({ ...rig, clearance: 0 });
  const swallowed = Rig.build({ ...rig, clearance: 3.5 });
  check(none.plate.clearance.length === 0 && none.obstacles[0].clearance.length === 0 && swallowed.plate.clearance.length === 0,
    "disk: no clearance curve for clearance 0, none inside a plate narrower than the clearance");
}

// ------------------------------------------------------------ polygons: vertices as given
{
  // A rectangle of the problem file is read as its four corners (rig_reader.cc).
  const corners = [[-2, -1], [3, -1], [3, 4], [-2, 4]];
  const L = Rig.build({ plate: { type: "polygon", vertices: corners }, obstacles: [], clearance: 0, x0: [0, 0] });
  check(JSON.stringify(L.plate.outline) === JSON.stringify(corners) && L.plate.type === "polygon",
    "polygon plate: the outline is the vertices, in order, the first not repeated");
}

// ------------------------------------------------------------ a square obstacle's clearance
// Outside the unit square [0, 1]^2 the distance is |(max(0, |x - 1/2| - 1/2), max(0, |y - 1/2| - 1/2))|;
// the parallel curve at distance c of a convex set has length perimeter + 2 pi c (Steiner).
for (const clockwise of [false, true]) {
  const square = [[0, 0], [1, 0], [1, 1], [0, 1]];
  const vertices = clockwise ? square.slice().reverse() : square;
  const c = 0.2;
  const L = Rig.build({ obstacles: [{ type: "polygon", vertices }], clearance: c, x0: [0, 0] });
  const curves = L.obstacles[0].clearance;
  const distance = (p) => Math.hypot(Math.max(0, Math.abs(p[0] - 0.5) - 0.5), Math.max(0, Math.abs(p[1] - 0.5) - 0.5));
  const error = maxOver(curves, (p) => Math.abs(distance(p) - c));
  const expected = 4 + 2 * Math.PI * c;
  const got = length(curves);
  check(error < kOnCurve && Math.abs(got - expected) / expected < kLengthRelative,
    "square obstacle (" + (clockwise ? "clockwise" : "counter-clockwise") + "): the clearance curve is at distance c outside, of length 4 + 2 pi c",
    `${curves.length} pieces, |distance - c| <= ${error.toExponential(1)}, length ${got.toFixed(5)} vs ${expected.toFixed(5)}`);
}

// ------------------------------------------------------------ a non-convex plate's clearance
// The L-shaped plate [0, 4] x [0, 2] u [0, 2] x [0, 4] (a reflex corner at (2, 2)) with clearance
// 1/2: the contact point's region is the L of arms [1/2, 7/2] x [1/2, 3/2] and [1/2, 3/2] x [1/2, 7/2]
// with the reflex corner rounded by a quarter circle of radius 1/2 about (2, 2). Its boundary has
// length 3 + 1 + 3/2 + 3/2 + 1 + 3 + pi / 4. Inside the L the distance to its edge is the smallest
// distance to its six sides (segments).
{
  const vertices = [[0, 0], [4, 0], [4, 2], [2, 2], [2, 4], [0, 4]];
  const c = 0.5;
  const L = Rig.build({ plate: { type: "polygon", vertices }, obstacles: [], clearance: c, x0: [0, 0] });
  const curves = L.plate.clearance;
  const sides = [[[0, 0], [4, 0]], [[4, 0], [4, 2]], [[4, 2], [2, 2]], [[2, 2], [2, 4]], [[2, 4], [0, 4]], [[0, 4], [0, 0]]];
  // Axis-aligned sides: the distance to a segment from its clamped coordinate.
  const toSide = (p, [a, b]) => {
    const qx = Math.min(Math.max(p[0], Math.min(a[0], b[0])), Math.max(a[0], b[0]));
    const qy = Math.min(Math.max(p[1], Math.min(a[1], b[1])), Math.max(a[1], b[1]));
    return Math.hypot(p[0] - qx, p[1] - qy);
  };
  const inL = (p) => (p[0] > 0 && p[0] < 4 && p[1] > 0 && p[1] < 2) || (p[0] > 0 && p[0] < 2 && p[1] > 0 && p[1] < 4);
  const error = maxOver(curves, (p) => Math.abs(Math.min(...sides.map((s) => toSide(p, s))) - c));
  const allInside = curves.flat().every(inL);
  const expected = 11 + Math.PI / 4;
  const got = length(curves);
  // The rounded corner: points of the curve near (2, 2) lie on the circle of radius 1/2 about it.
  const corner = curves.flat().filter((p) => p[0] > 2 - 1e-9 && p[1] > 2 - 1e-9);
  check(error < kOnCurve && allInside && Math.abs(got - expected) / expected < kLengthRelative && corner.length === 0,
    "L-shaped plate: the clearance curve is inside, at distance c from the edge, rounded at the reflex corner, of length 11 + pi/4",
    `${curves.length} pieces, |distance - c| <= ${error.toExponential(1)}, length ${got.toFixed(5)} vs ${expected.toFixed(5)}`);
  const arc = curves.flat().filter((p) => p[0] > 1.5 + 1e-6 && p[1] > 1.5 + 1e-6);
  const arcError = Math.max(...arc.map((p) => Math.abs(Math.hypot(p[0] - 2, p[1] - 2) - c)));
  check(arc.length > 3 && arcError < kOnCurve, "L-shaped plate: the reflex corner's piece is the circle of radius c about it",
    `${arc.length} points, |r - c| <= ${arcError.toExponential(1)}`);
}

// ------------------------------------------------------------ the stroke
// The upper plate's reference point starts above x0 and is at x0 + 2 (x - x0) when the contact point
// is at x; the limit |2 (x - x0)_i| <= s_i (rig_limits.h) makes the contact point's box x0 +- s/2 and
// the reference point's box x0 +- s.
{
  const x0 = [1, -2], s = [4, 3];
  const L = Rig.build({ obstacles: [], clearance: 0, stroke: s, x0 });
  const expectedUpper = [[-3, -5], [5, -5], [5, 1], [-3, 1]];
  const upperError = Math.max(...L.stroke.upper.map((p, k) => Math.hypot(p[0] - expectedUpper[k][0], p[1] - expectedUpper[k][1])));
  // Each contact corner meets the limit with equality in both coordinates, and the upper plate's
  // reference point is at the matching upper corner when the contact point is there.
  const limitError = Math.max(...L.stroke.contact.map((p) => Math.max(Math.abs(Math.abs(2 * (p[0] - x0[0])) - s[0]), Math.abs(Math.abs(2 * (p[1] - x0[1])) - s[1]))));
  const mapError = Math.max(...L.stroke.contact.map((p, k) => Math.hypot(x0[0] + 2 * (p[0] - x0[0]) - L.stroke.upper[k][0], x0[1] + 2 * (p[1] - x0[1]) - L.stroke.upper[k][1])));
  check(upperError < kExact && limitError < kExact && mapError < kExact &&
    L.points.some((p) => p[0] === -3 && p[1] === -5),
    "stroke: the upper plate's box is x0 +- s, the contact point's x0 +- s/2, corner to corner under x -> x0 + 2 (x - x0), in the view's extent",
    `corner errors ${upperError.toExponential(1)}, ${limitError.toExponential(1)}, ${mapError.toExponential(1)}`);
  const noStroke = Rig.build({ obstacles: [], clearance: 0, x0 });
  check(noStroke.stroke === null && noStroke.plate === null && noStroke.points.length === 0,
    "a rig of actuator limits only: nothing drawn on the plates");
}

// ------------------------------------------------------------ the work budget
// Many large polygons (a problem file may hold 1000 of 1000 vertices): their clearance curves would
// take minutes of script; past the budget they are left out (and say so), the outlines kept. Here
// twenty 200-gons, each curve 200 x (400 pieces x 9 samples) = 7.2e5 distances, against 3e6.
{
  const polygon = (cx) => Array.from({ length: 200 }, (_, k) => [cx + Math.cos((2 * Math.PI * k) / 200), Math.sin((2 * Math.PI * k) / 200)]);
  const obstacles = Array.from({ length: 20 }, (_, i) => ({ type: "polygon", vertices: polygon(3 * i) }));
  const started = Date.now();
  const L = Rig.build({ obstacles, clearance: 0.05, x0: [0, 0] }, { left: 3e6 });
  const seconds = (Date.now() - started) / 1000;
  const drawn = L.obstacles.filter((o) => !o.clearanceSkipped);
  const onCurve = drawn.length ? maxOver(drawn[0].clearance, (p) => Math.abs(Rig.edgeDistance(obstacles[0].vertices, p) - 0.05)) : 1;
  check(drawn.length === 4 && L.obstacles.every((o) => o.outline.length === 200) && onCurve < kOnCurve,
    "twenty 200-gon obstacles: clearance curves within the work budget, the rest outlined only",
    `${drawn.length} of 20 drawn in ${seconds.toFixed(2)} s, the first at distance c to ${onCurve.toExponential(1)}`);
}

console.log(failures ? `# ${failures} failed` : "# all passed");
process.exit(failures ? 1 : 0);
