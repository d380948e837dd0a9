// Writes scenes/bunny.obj from the npm package `bunny` (the Stanford bunny as positions and
// triangle cells; public domain). Run once; the OBJ is kept in the repository:
//   cd "$(mktemp -d)" && npm install bunny && node /path/to/luz/scripts/make_bunny_obj.js \
//       > /path/to/luz/scenes/bunny.obj
// The package is looked up from the current folder (its node_modules) or given as argument 1.
"use strict";

const where = process.argv[2] || process.cwd();
const bunnyPath = require.resolve(process.argv[2] ? where : "bunny", { paths: [where] });
const bunny = require(bunnyPath);
const pkg = require(require.resolve("bunny/package.json", { paths: [where] }));

const lines = [];
lines.push("# The Stanford bunny (Stanford 3D Scanning Repository, via the npm package");
lines.push(`# "bunny" ${pkg.version} by Mikola Lysenko, licence: ${pkg.license}).`);
lines.push("# Written by luz/scripts/make_bunny_obj.js; y up, sitting on y = 0,");
lines.push("# counter-clockwise faces seen from outside.");
lines.push(`# ${bunny.positions.length} vertices, ${bunny.cells.length} triangles`);
for (const p of bunny.positions) lines.push(`v ${p[0]} ${p[1]} ${p[2]}`);
for (const c of bunny.cells) lines.push(`f ${c[0] + 1} ${c[1] + 1} ${c[2] + 1}`);
process.stdout.write(lines.join("\n") + "\n");
