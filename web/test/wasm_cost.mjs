// Physics cost in the page's wasm, variants interleaved:
//   web/test/wasm_cost.mjs DIST... [--rounds N] [--warmup N]   (LEVELS=a,b,c to choose the levels)
// opens each DIST's page (served by web/serve.py) with ?check=1 on LEVELS and reads the report's
// wall_ms (stepping, readings and checks, no drawing), round-robin over the variants, so that a
// changing load falls on all of them alike. Prints each level's median wall_ms per variant.
import { chromium } from "playwright-core";
import { spawn } from "node:child_process";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const root = resolve(dirname(fileURLToPath(import.meta.url)), "../..");
const args = process.argv.slice(2);
let rounds = 5;
let warmup = 2; // loads whose wall_ms is dropped: V8 runs its baseline code until the optimised code (and its cache) is there
const dists = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === "--rounds") rounds = Number(args[++i]);
  else if (args[i] === "--warmup") warmup = Number(args[++i]);
  else dists.push(resolve(args[i]));
}
if (dists.length === 0) {
  console.error("usage: web/test/wasm_cost.mjs DIST... [--rounds N] [--warmup N] (each DIST a folder web/build.sh made)");
  process.exit(2);
}
const LEVELS = (process.env.LEVELS ?? "stress/pyramid_20.ron,kinematics/classic_four_bar.ron,kinetics/physical_pendulum.ron").split(",");
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
// A port each (consecutive: two variants never share one), and each server must still be running
// when it answers, else another program on its port would be timed in its place.
const firstPort = 9100 + Math.floor(Math.random() * 800);
const servers = dists.map((d, k) => {
  const port = firstPort + k;
  const p = spawn("python3", [join(root, "web/serve.py"), "--quiet", "--port", String(port), "--dir", d], { stdio: "ignore" });
  const s = { d, port, p, exited: false };
  p.on("exit", () => { s.exited = true; });
  return s;
});
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium", headless: true,
  args: ["--no-sandbox", "--no-first-run", "--disable-background-networking", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
const wall = {};
try {
  for (const s of servers) {
    let up = false;
    for (let i = 0; i < 50 && !up && !s.exited; i++) { try { await fetch(`http://127.0.0.1:${s.port}/`); up = true; } catch { await sleep(100); } }
    if (!up || s.exited) throw new Error(`${s.d}: its server on port ${s.port} did not start (port taken?)`);
  }
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  for (let r = 0; r < warmup + rounds; r++) {
    for (const s of servers) {
      for (const level of LEVELS) {
        await page.goto(`http://127.0.0.1:${s.port}/?check=1&level=${level}`);
        const t0 = Date.now();
        for (;;) {
          const st = JSON.parse((await page.textContent("#rigidlab-status")) || "null");
          if (st && st.check === "done") break;
          if (Date.now() - t0 > 300000) throw new Error(`${s.d} ${level}: no report`);
          await sleep(50);
        }
        const rep = JSON.parse(await page.textContent("#rigidlab-report")).levels[0];
        if (r >= warmup) ((wall[s.d] ??= {})[level] ??= []).push(rep.wall_ms);
      }
    }
  }
} finally {
  await browser.close();
  for (const s of servers) s.p.kill();
}
const med = (a) => { const b = [...a].sort((x, y) => x - y); return b[Math.floor(b.length / 2)]; };
for (const level of LEVELS) {
  const base = med(wall[dists[0]][level]);
  for (const d of dists) {
    const m = med(wall[d][level]);
    console.log(`${level}\t${d}\tmedian ${m.toFixed(1)} ms\t${(m / base).toFixed(3)}x the first\t[${wall[d][level].map((x) => x.toFixed(0)).join(" ")}]`);
  }
}
