// The browser test's driver: serves web/dist, opens it in headless Chromium (Debian's, through
// playwright-core) as a student would, and records what it saw into OUT (default
// target/web-test) for tests/suite/app/web_page.rs to judge against the core:
//   check.json      the page's own `?check=1` report of the levels in CHECK_LEVELS;
//   check_student.json  the same for levels with parameters and a student id (`&student=`);
//   pendulum.png    the simple pendulum played to its end (t = 0.8 s), as the page drew it;
//   status.json     the page's status at that moment (time, view mapping, frame rate);
//   answered.png / answered.json   after typing an answer into the first question's box;
//   progress.json   the course's progress in localStorage: saved after that answer, shown again
//                   after a reload; a corrupt value reported, kept aside, never overwritten;
//                   the first-steps tour's steps ticked, before and after the reload
//                   (reloaded.png: the page after the reload, its tour's count);
//   typed.json / typed.png   answers typed with no pause right after a click into each box;
//   built.png       a pendulum built in the page with the editor's buttons and tools, swinging;
//   pyramid.png     the 210-box pyramid playing with every overlay on;
//   unknown.png / unknown.json   the page opened with a ?level= the library does not have;
//   predict_held.png / predict_revealed.png / predict.json   the pendulum opened with
//                   &predict=1&play=1: held at t = 0 through Space and 3 s, then, its two
//                   answers typed, played to its end with the predictions beside the run's values;
//   links.json      a level opened from a #level= link, corrupt links refused, an assignment
//                   fetched with ?url= and a missing one refused; link.png the linked level;
//   browser.json    how the wasm came (its Content-Encoding and size on the wire), timings: page
//                   open to first frame (wasm compiled earlier in the session, and cold: a new
//                   browser context), frame rates while playing, the CPU a paused page takes
//                   over 10 s (paused_10s), the loading bar's first and last byte counts;
//   loading.json / loading.png   the cold page over a throttled line: the loading note sampled
//                   every 100 ms until the first frame, and a screenshot of it.
// Usage: node web/test/browser.mjs [OUT]   (exit 1 with the reason when a step fails)
import { chromium } from "playwright-core";
import { spawn } from "node:child_process";
import { cpSync, mkdirSync, writeFileSync, existsSync, readdirSync, readFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { deflateRawSync } from "node:zlib";
import { fileURLToPath } from "node:url";

const root = resolve(dirname(fileURLToPath(import.meta.url)), "../..");
const dist = join(root, "web/dist");
const out = resolve(process.argv[2] ?? join(root, "target/web-test"));
const chromiumPath = process.env.CHROMIUM ?? "/usr/bin/chromium";
// Levels whose numbers the page must reproduce (tests/suite/app/web_page.rs compares them with the core).
const CHECK_LEVELS = [
  "kinetics/simple_pendulum.ron",
  "kinetics/physical_pendulum.ron",
  "impact/jh_P9.11.1_oblique_spheres.ron",
  "energy/torsion_spring_flywheel.ron",
  "kinematics/classic_four_bar.ron",
  "momentum/bar_struck_at_percussion.ron",
  "virtual-work/zh_slider_crank_static_servo.ron",
  "kinetics/classic_atwood_massive_pulley.ron",
];
// Levels with parameters and the student ids the page checks them for (check_student.json).
const STUDENT_LEVELS = [
  ["energy/classic_spring_block_param.ron", "alice"],
  ["kinetics/incline_friction_param.ron", "s-042 Ölçü"],
];
const ANSWER = process.env.ANSWER ?? "3.13"; // v_bottom = sqrt(g L) = 3.1321 m/s (the level's comment)

function fail(why) {
  console.error(`browser test: ${why}`);
  process.exit(1);
}
if (!existsSync(join(dist, "index.html"))) fail(`no ${dist}/index.html: run web/build.sh first`);
if (!existsSync(chromiumPath)) fail(`no Chromium at ${chromiumPath} (apt-get install chromium, or set CHROMIUM)`);
mkdirSync(out, { recursive: true });

// web/serve.py, as docs/web.md tells a teacher to serve the page: .wasm as application/wasm (what
// WebAssembly.instantiateStreaming needs), compressed as the browser accepts.
const port = 8000 + Math.floor(Math.random() * 1000);
const server = spawn("python3", [join(root, "web/serve.py"), "--quiet", "--port", String(port), "--dir", dist], { stdio: "ignore" });
const base = `http://127.0.0.1:${port}/`;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// The flags this machine needs (no network, no GPU): WebGL2 through SwiftShader, on the CPU.
const browser = await chromium.launch({
  executablePath: chromiumPath,
  headless: true,
  args: [
    "--no-sandbox", "--no-first-run", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--disable-quic", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--ignore-gpu-blocklist",
  ],
});
const summary = {};
try {
  for (let i = 0; i < 50; i++) {
    try { await fetch(base); break; } catch { await sleep(100); }
  }
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const logs = [];
  page.on("console", (m) => logs.push(`${m.type()}: ${m.text()}`));
  page.on("pageerror", (e) => logs.push(`pageerror: ${e}`));
  // How the wasm came: its Content-Encoding and the bytes on the wire (the first load only).
  // The level library likewise (levels.json, fetched beside the wasm since 2026-12-07).
  page.on("response", async (r) => {
    const key = r.url().endsWith("rigidlab_bg.wasm") ? "wasm" : r.url().endsWith("levels.json") ? "library" : null;
    if (!key || summary[key]) return;
    const h = await r.allHeaders();
    summary[key] = { encoding: h["content-encoding"] ?? "identity", bytes_sent: Number(h["content-length"] ?? -1) };
  });
  const status = async () => JSON.parse((await page.textContent("#rigidlab-status")) || "null");
  const waitStatus = async (what, ok, seconds) => {
    const t0 = Date.now();
    for (;;) {
      let s = null;
      try { s = await status(); } catch {}
      if (s && ok(s)) return s;
      if (Date.now() - t0 > seconds * 1000) {
        writeFileSync(join(out, "console.log"), logs.join("\n"));
        fail(`${what} did not happen within ${seconds} s; last status ${JSON.stringify(s)}; console in ${out}/console.log`);
      }
      await sleep(50);
    }
  };

  // 1. The numbers: the page runs the levels with the core and prints the report.
  const checks = [];
  for (const level of CHECK_LEVELS) {
    await page.goto(`${base}?check=1&level=${level}`);
    await waitStatus(`the page's check of ${level}`, (s) => s.check === "done", 120);
    checks.push(...JSON.parse(await page.textContent("#rigidlab-report")).levels);
  }
  writeFileSync(join(out, "check.json"), JSON.stringify({ passed: checks.every((l) => l.passed), levels: checks }, null, 1));

  // 1b. A student's own numbers: the page's check of a level with parameters for a student id
  //     (`&student=`), which must be the variant `rigidlab check --student ID` runs natively.
  const variants = [];
  for (const [level, student] of STUDENT_LEVELS) {
    await page.goto(`${base}?check=1&level=${level}&student=${encodeURIComponent(student)}`);
    await waitStatus(`the page's check of ${level} for ${student}`, (s) => s.check === "done", 120);
    variants.push({ student, report: JSON.parse(await page.textContent("#rigidlab-report")).levels[0] });
  }
  writeFileSync(join(out, "check_student.json"), JSON.stringify(variants, null, 1));

  // 2. A student opens the pendulum and plays it to its end.
  const t0 = Date.now();
  await page.goto(`${base}?level=kinetics/simple_pendulum.ron&play=1`);
  const first = await waitStatus("the first frame", (s) => s.frames >= 1, 60);
  summary.open_to_first_frame_s = (Date.now() - t0) / 1000;
  const end = await waitStatus("the pendulum's end (t = 0.8 s)", (s) => s.paused && s.at_end, 120);
  summary.pendulum_end = { t: end.t, step: end.step };
  await sleep(300); // a few more frames of the paused state on screen
  const still = await status();
  writeFileSync(join(out, "status.json"), JSON.stringify(still, null, 1));
  await page.screenshot({ path: join(out, "pendulum.png") });

  // 3. The student types an answer into the first question's box and presses Enter.
  // The questions sit under the statement in the left panel: scroll it until the box shows.
  const answerBox = async (k) => {
    let q = (await status()).answers[k];
    for (let i = 0; i < 20 && q && q.box && q.box[1] + q.box[3] > 780; i++) {
      await page.mouse.move(150, 600);
      await page.mouse.wheel(0, 200);
      const f = (await status()).frames;
      await waitStatus("a frame after scrolling", (s) => s.frames >= f + 2, 30);
      q = (await status()).answers[k];
    }
    if (!q || !q.box) fail(`no answer box ${k} in the status: ${JSON.stringify((await status()).answers)}`);
    const [, y, , h] = q.box;
    if (y + h > 800) fail(`the answer box stays below the page (${q.box}) after scrolling`);
    return q.box;
  };
  const typeAnswer = async (k, text) => {
    const [x, y, w, h] = await answerBox(k);
    await page.mouse.click(x + w / 2, y + h / 2);
    // Keys typed before egui has seen the click would go nowhere: let it focus the box first.
    const f0 = (await status()).frames;
    await waitStatus("two frames after the click", (s) => s.frames >= f0 + 2, 30);
    await page.keyboard.type(text, { delay: 100 });
    await page.keyboard.press("Enter");
  };
  await typeAnswer(0, ANSWER);
  const graded = await waitStatus("the grade of the typed answer", (s) => s.answers[0].grade, 30);
  writeFileSync(join(out, "answered.json"), JSON.stringify(graded, null, 1));
  await page.screenshot({ path: join(out, "answered.png") });
  summary.grade = graded.answers[0].grade;
  summary.typed = graded.answers[0].typed;

  // 3b. Progress in the browser's localStorage: the graded answer is stored, a reload shows it in
  //     the course; a corrupt value is reported, kept aside under rigidlab.progress.bad and not
  //     overwritten when the next answer saves progress afresh (progress.json).
  const KEY = "rigidlab.progress";
  const stored = () => page.evaluate(() => Object.fromEntries(Object.keys(localStorage).map((k) => [k, localStorage.getItem(k)])));
  //     The first-steps tour's steps ticked are kept with it (its count reset on every reload
  //     before 2026-12-07): recorded before the reload, after it, and after the corrupt value.
  const progress = { saved: (await stored())[KEY] ?? null, tour_saved: (await status()).course.tour ?? null };
  await page.reload();
  const reloaded = await waitStatus("the course after a reload", (s) => s.frames >= 2 && s.course, 60);
  progress.after_reload = reloaded.course;
  progress.tour_after_reload = reloaded.course.tour ?? null;
  await page.screenshot({ path: join(out, "reloaded.png") });
  const CORRUPT = "Progress(levels: [ this is not progress";
  await page.evaluate(([k, v]) => localStorage.setItem(k, v), [KEY, CORRUPT]);
  await page.reload();
  const refusedProgress = await waitStatus("the corrupt progress reported", (s) => s.frames >= 2 && s.course && s.course.problem, 60);
  progress.corrupt = { course: refusedProgress.course, message: refusedProgress.message, stored: await stored(), tour: refusedProgress.course.tour ?? null };
  await typeAnswer(0, ANSWER);
  await waitStatus("the grade after the corrupt progress", (s) => s.answers[0].grade, 30);
  progress.corrupt.after_answer = await stored();
  progress.corrupt_text = CORRUPT;
  writeFileSync(join(out, "progress.json"), JSON.stringify(progress, null, 1));
  // The later steps start with no progress stored, as before this step.
  await page.evaluate(() => localStorage.clear());

  // 3c. Typed at once after the click, as a student types (typed.json): a click into a box and
  //     the answer typed with no pause, at the page's own low frame rate, into the first box and
  //     then (the first still focused) into the second, three times on a fresh page. Before
  //     2026-12-07 the keys that came in the click's frame were lost ("7.104" became ".104") or
  //     went to the box focused before. No wait between the click and the keys, on purpose.
  const typedAtOnce = [];
  for (const [a, b] of [["7.104", "19.62"], ["3.13", "0.525"], ["42", "8.25"]]) {
    await page.goto(`${base}?level=kinetics/simple_pendulum.ron`);
    await waitStatus("the pendulum's first frames", (s) => s.frames >= 2, 60);
    const boxes = [await answerBox(0), await answerBox(1)];
    const before = { frames: (await status()).frames, at: Date.now() };
    for (const [k, text] of [[0, a], [1, b]]) {
      const [x, y, w, h] = boxes[k];
      await page.mouse.click(x + w / 2, y + h / 2);
      await page.keyboard.type(text);
    }
    // How many frames the page drew while the two clicks and the keys came: fewer than the
    // clicks and keys, so that some of them shared a frame (the condition of the lost keys).
    const during = { frames: (await status()).frames - before.frames, ms: Date.now() - before.at, inputs: 2 + a.length + b.length };
    // A paused page draws on input: small moves over the statement bring frames until the boxes
    // hold the answers, or 15 s (a click and the keys after it take a frame each).
    const f = (await status()).frames;
    let s = await status();
    for (let i = 0; i < 75 && !(s.answers[0].typed === a && s.answers[1].typed === b); i++) {
      await page.mouse.move(150 + (i % 2), 100);
      await sleep(200);
      s = await status();
    }
    typedAtOnce.push({ want: [a, b], typed: [s.answers[0].typed, s.answers[1].typed], during, frames_after: s.frames - f });
  }
  writeFileSync(join(out, "typed.json"), JSON.stringify(typedAtOnce, null, 1));
  await page.screenshot({ path: join(out, "typed.png") });
  summary.typed_at_once = typedAtOnce;
  const lost = typedAtOnce.filter((r) => r.typed[0] !== r.want[0] || r.typed[1] !== r.want[1]);
  if (lost.length) fail(`keys typed at once after a click did not all reach the box: ${JSON.stringify(lost)}`);

  // 4. The student opens level files from their computer: a good one opens, a broken one says
  //    where it is broken and leaves the open level alone.
  writeFileSync(join(out, "broken.ron"), "(title: \"broken\", bodies: [ (name: \"a\" ]");
  await page.setInputFiles("#pick", join(root, "levels/impact/central_impact.ron"));
  const opened = await waitStatus("the picked level to open", (s) => s.level.endsWith("central_impact.ron"), 30);
  await page.setInputFiles("#pick", join(out, "broken.ron"));
  const refused = await waitStatus("the broken file's error", (s) => s.message && !s.message.ok, 30);
  if (!refused.level.endsWith("central_impact.ron")) fail(`a broken file replaced the open level: ${refused.level}`);
  if (!/broken\.ron:\d+:\d+/.test(refused.message.text)) fail(`the error does not locate the fault: ${refused.message.text}`);
  summary.picked = { opened: opened.title, refused: refused.message.text.split("\n").slice(0, 2).join(" / ") };

  // 5. The student builds a pendulum in the page with the editor, by clicking: new scene, the
  //    bar tool and a click in the scene, the pin tool and a click at the bar's left end; then
  //    plays it. The page publishes where its build buttons are and how metres map to pixels.
  await page.goto(`${base}?level=kinetics/simple_pendulum.ron`);
  await waitStatus("the first frame", (s) => s.frames >= 2, 60);
  const button = async (name) => {
    let b = (await status()).buttons[name];
    for (let i = 0; i < 20 && b && b[1] + b[3] > 780; i++) {
      await page.mouse.move(1150, 500);
      await page.mouse.wheel(0, 200);
      const f = (await status()).frames;
      await waitStatus("a frame after scrolling", (s) => s.frames >= f + 2, 30);
      b = (await status()).buttons[name];
    }
    if (!b) fail(`no "${name}" button in the status`);
    return b;
  };
  const clickButton = async (name) => {
    const [bx, by, bw, bh] = await button(name);
    const f = (await status()).frames;
    await page.mouse.click(bx + bw / 2, by + bh / 2);
    await waitStatus(`a frame after clicking "${name}"`, (s) => s.frames >= f + 2, 30);
  };
  const toScreen = (s, [wx, wy]) => {
    const [x0, y0, x1, y1] = s.view.viewport;
    return [(x0 + x1) / 2 + (wx - s.view.center[0]) / s.view.m_per_px, (y0 + y1) / 2 - (wy - s.view.center[1]) / s.view.m_per_px];
  };
  await clickButton("new scene");
  let built = await waitStatus("the new scene", (s) => s.bodies === 1 && s.title === "My scene", 30);
  await clickButton("place bar");
  built = await status();
  // The new scene's ground is 8 m wide: a bar is 2 m long. Put its center 2 m above the ground.
  let [sx, sy] = toScreen(built, [0.5, 2.0]);
  await page.mouse.click(sx, sy);
  built = await waitStatus("the bar placed", (s) => s.bodies === 2, 30);
  await clickButton("join pin");
  built = await status();
  [sx, sy] = toScreen(built, [-0.49, 2.0]);
  await page.mouse.click(sx, sy);
  built = await waitStatus("the pin made", (s) => s.joints === 1, 30);
  await page.keyboard.press("1");
  await page.keyboard.press(" ");
  built = await waitStatus("the built pendulum swinging", (s) => !s.paused && s.t > 1.0, 60);
  await page.screenshot({ path: join(out, "built.png") });
  summary.built = { bodies: built.bodies, joints: built.joints, t: built.t, editor: built.editor };

  // 6. Frame rate while playing, with every overlay on (keys A C F K H join the default V T L):
  //    frames counted over 2.5 s after a 1 s warm-up (shaders compiled; the pendulum's 3.6 s
  //    run does not end inside the window if the page keeps real time).
  const playFps = async (level) => {
    await page.goto(`${base}?level=${level}`);
    await waitStatus(`${level}'s first frame`, (s) => s.frames >= 2, 60);
    await page.mouse.click(450, 700); // focus the canvas (an empty spot of the scene)
    const f = (await status()).frames;
    await waitStatus("two frames after the click", (s) => s.frames >= f + 2, 30);
    for (const k of ["a", "c", "f", "k", "h", " "]) await page.keyboard.press(k);
    await waitStatus(`${level} playing`, (s) => !s.paused, 30);
    await sleep(1000);
    const a = await status();
    const t0 = Date.now();
    await sleep(2500);
    const b = await status();
    return {
      fps: (b.frames - a.frames) / ((Date.now() - t0) / 1000),
      frame_ms_median: b.frame_ms_median,
      // Simulated seconds per real second (1 = real time); null when the level ended inside.
      sim_rate: b.paused ? null : (b.t - a.t) / ((Date.now() - t0) / 1000),
    };
  };
  summary.playing = {
    "kinetics/physical_pendulum.ron": await playFps("kinetics/physical_pendulum.ron"),
    "stress/pyramid_20.ron": await playFps("stress/pyramid_20.ron"),
  };
  await page.screenshot({ path: join(out, "pyramid.png") });

  // 7. An unknown ?level=: an error and the library, not another exercise (unknown.json/.png).
  await page.goto(`${base}?level=kinetics/no_such_level.ron`);
  const unknown = await waitStatus("the unknown level's message", (s) => s.frames >= 2 && s.message, 60);
  await page.screenshot({ path: join(out, "unknown.png") });
  writeFileSync(join(out, "unknown.json"), JSON.stringify(unknown, null, 1));
  summary.unknown = { title: unknown.title, bodies: unknown.bodies, message: unknown.message };

  // 8. Predict first, by the link: the pendulum waits at t = 0 (even with &play=1 and Space
  //    pressed) until both questions have an answer, then plays to its end and shows them.
  await page.goto(`${base}?level=kinetics/simple_pendulum.ron&predict=1&play=1`);
  await waitStatus("the predict-first page's first frames", (s) => s.frames >= 2 && s.predict === "predicting", 60);
  await page.mouse.click(450, 700); // focus the canvas (an empty spot of the scene)
  await page.keyboard.press(" ");
  await sleep(3000);
  const held = await status();
  if (held.t !== 0 || held.step !== 0 || !held.paused) fail(`the predict-first run moved before the answers: t = ${held.t}, step ${held.step}`);
  if (!held.message || !/answer first/.test(held.message.text)) fail(`Space was not refused with "answer first": ${JSON.stringify(held.message)}`);
  await page.screenshot({ path: join(out, "predict_held.png") });
  await typeAnswer(0, ANSWER);
  const between = await status();
  if (between.t !== 0 || between.answers[0].grade !== null) fail(`one answer of two: the run moved or the grade showed: ${JSON.stringify(between)}`);
  await typeAnswer(1, "19.62"); // the rod's tension at the bottom, m g (3 - 2 cos 60) = 2 m g = 19.62 N
  const moving = await waitStatus("the motion after the answers", (s) => s.t > 0 && s.predict !== "predicting", 30);
  const revealed = await waitStatus("the predictions beside the run's values", (s) => s.predict === "revealed", 120);
  await sleep(300);
  await page.screenshot({ path: join(out, "predict_revealed.png") });
  summary.predict = { held: { t: held.t, step: held.step, message: held.message.text }, moving: { t: moving.t, predict: moving.predict }, revealed: { t: revealed.t } };
  writeFileSync(join(out, "predict.json"), JSON.stringify({ held, revealed }, null, 1));

  // 9. Links. A level carried in the link itself: compressed here with Node's zlib (raw DEFLATE)
  //    and base64url, independently of rigidlab's encoder, so the page is held to the format
  //    docs/web.md states. Then corrupt links: an error naming what is wrong, and no exercise.
  const linked = "levels/momentum/bar_struck_at_percussion.ron";
  const linkedText = readFileSync(join(root, linked), "utf8");
  const linkedTitle = /title:\s*"([^"]*)"/.exec(linkedText)[1];
  const data = deflateRawSync(Buffer.from(linkedText, "utf8"), { level: 9 }).toString("base64url");
  const links = { data_chars: data.length };
  const openFresh = async (url) => {
    await page.goto("about:blank"); // a change of the fragment alone would not reload the page
    await page.goto(url);
  };
  await openFresh(`${base}#level=${data}&name=bar_struck_at_percussion.ron`);
  const fromLink = await waitStatus("the linked level", (s) => s.frames >= 2 && s.title === linkedTitle, 60);
  if (fromLink.level !== "bar_struck_at_percussion.ron") fail(`the linked level opened as ${fromLink.level}`);
  await page.screenshot({ path: join(out, "link.png") });
  links.opened = { level: fromLink.level, title: fromLink.title, questions: fromLink.answers.length };
  const corrupt = {
    // A character base64url does not have, in the middle of the data.
    bad_base64: `${data.slice(0, 40)}*${data.slice(41)}`,
    // The data cut short, as a mail program may wrap it (a whole number of 4-character groups).
    cut: data.slice(0, 4 * Math.floor(data.length / 8)),
    // Valid base64url and valid DEFLATE of a text that is not a level.
    not_a_level: deflateRawSync(Buffer.from("hello, class")).toString("base64url"),
  };
  const expect = { bad_base64: /not valid base64url at character 41/, cut: /does not decompress/, not_a_level: /link\.ron:1:/ };
  links.refused = {};
  for (const [kind, d] of Object.entries(corrupt)) {
    await openFresh(`${base}#level=${d}`);
    const s = await waitStatus(`the ${kind} link's error`, (s) => s.frames >= 2 && s.message, 60);
    if (s.message.ok || !expect[kind].test(s.message.text)) fail(`the ${kind} link: ${JSON.stringify(s.message)}`);
    if (s.title !== "Empty scene" || s.bodies !== 0) fail(`the ${kind} link opened an exercise: ${s.title}`);
    links.refused[kind] = s.message.text.split("\n")[0];
  }
  //    An assignment served beside the page, fetched with ?url=: its levels in order, the first
  //    opened; a path the server does not have says so.
  cpSync(join(root, "assignments/intro"), join(dist, "assignments/intro"), { recursive: true });
  await openFresh(`${base}?url=assignments/intro/assignment.ron`);
  const assigned = await waitStatus("the fetched assignment", (s) => s.frames >= 2 && s.assignment && s.title !== "Empty scene", 60);
  const manifest = readFileSync(join(root, "assignments/intro/assignment.ron"), "utf8");
  const want = [...manifest.matchAll(/^\s*"([^"]+\.ron)",/gm)].map((m) => `/assignments/intro/${m[1]}`);
  const got = assigned.assignment.levels.map((l) => l.path);
  if (JSON.stringify(got) !== JSON.stringify(want)) fail(`the assignment's levels: ${JSON.stringify(got)}, want ${JSON.stringify(want)}`);
  if (assigned.assignment.levels.some((l) => l.error)) fail(`a level of the assignment did not load: ${JSON.stringify(assigned.assignment)}`);
  if (assigned.level !== want[0]) fail(`the assignment opened ${assigned.level}, not its first level ${want[0]}`);
  await page.screenshot({ path: join(out, "assignment.png") });
  links.assignment = { title: assigned.assignment.title, due: assigned.assignment.due, levels: got, opened: assigned.title };
  await openFresh(`${base}?url=assignments/none/assignment.ron`);
  const missing = await waitStatus("the missing assignment's error", (s) => s.frames >= 2 && s.message && !s.message.ok, 60);
  if (!/404/.test(missing.message.text) || missing.title !== "Empty scene") fail(`the missing assignment: ${JSON.stringify(missing.message)}`);
  links.missing = missing.message.text.split("\n")[0];
  writeFileSync(join(out, "links.json"), JSON.stringify(links, null, 1));
  summary.links = links;

  // 10. A paused page leaves the CPU alone: the CPU time of every Chromium process (/proc,
  //    utime + stime) over 10 s with the simple pendulum open and paused, after 3 s to settle.
  const cpuSeconds = () => {
    const tick = 100; // USER_HZ on Linux
    let total = 0;
    for (const pid of readdirSync("/proc").filter((d) => /^\d+$/.test(d))) {
      try {
        const stat = readFileSync(`/proc/${pid}/stat`, "utf8");
        const comm = stat.slice(stat.indexOf("(") + 1, stat.lastIndexOf(")"));
        if (!/chrom/i.test(comm)) continue;
        const f = stat.slice(stat.lastIndexOf(")") + 2).split(" ");
        total += (Number(f[11]) + Number(f[12])) / tick;
      } catch {}
    }
    return total;
  };
  await page.goto(`${base}?level=kinetics/simple_pendulum.ron`);
  await waitStatus("the paused pendulum's first frame", (s) => s.frames >= 2 && s.paused, 60);
  await sleep(3000);
  const c0 = cpuSeconds();
  const pausedFrames = (await status()).frames;
  await sleep(10000);
  summary.paused_10s = { cpu_s: cpuSeconds() - c0, frames: (await status()).frames - pausedFrames };

  // 11. Opened cold, as a student opens it the first time: a new browser context (no cached and no
  //     compiled wasm). First on this machine's loopback, timing the first frame; then over a
  //     slow line (Chromium's network throttling, LOADING_RATE bytes per second on the wire),
  //     sampling the loading note every 100 ms until the first frame removes it: the bar and the
  //     megabytes received must show while the wasm comes (loading.json, loading.png).
  const cold = async (rate) => {
    const ctx = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    const p = await ctx.newPage();
    if (rate) {
      const cdp = await ctx.newCDPSession(p);
      await cdp.send("Network.enable");
      await cdp.send("Network.emulateNetworkConditions", { offline: false, latency: 20, downloadThroughput: rate, uploadThroughput: -1 });
    }
    const t0 = Date.now();
    await p.goto(`${base}?level=kinetics/simple_pendulum.ron`, { waitUntil: "commit" });
    const samples = [];
    let shot = false;
    for (;;) {
      let s;
      try {
        s = await p.evaluate(() => {
          const note = document.getElementById("loading");
          const drawn = document.getElementById("rigidlab-status")?.textContent ?? "";
          if (!note) return { gone: true, drawn: drawn.length > 0 };
          const bar = document.getElementById("loading-bar");
          const r = bar.getBoundingClientRect();
          const style = getComputedStyle(note);
          return {
            gone: false,
            drawn: drawn.length > 0,
            count: document.getElementById("loading-count").textContent,
            bar: bar.hasAttribute("value") ? bar.value : null,
            visible: r.width > 0 && r.height > 0 && style.display !== "none" && style.visibility !== "hidden",
          };
        });
      } catch {
        s = null; // the document is being replaced
      }
      const at_s = (Date.now() - t0) / 1000;
      if (s && s.gone && s.drawn) {
        await ctx.close();
        return { first_frame_s: at_s, samples };
      }
      if (s && !s.gone && s.count) {
        samples.push({ at_s, count: s.count, bar: s.bar, visible: s.visible, drawn: s.drawn });
        if (rate && !shot) {
          await p.screenshot({ path: join(out, "loading.png") });
          shot = true;
        }
      }
      if (at_s > 180) fail(`the cold page drew no frame within 180 s (rate ${rate}); last ${JSON.stringify(s)}`);
      await sleep(100);
    }
  };
  summary.cold_first_frame_s = (await cold(null)).first_frame_s;
  const LOADING_RATE = 2_000_000; // bytes per second: a 16 Mbit/s share of a classroom's line
  const loading = await cold(LOADING_RATE);
  loading.rate_bytes_per_s = LOADING_RATE;
  writeFileSync(join(out, "loading.json"), JSON.stringify(loading, null, 1));
  const counted = loading.samples.filter((s) => /^[\d.]+ of [\d.]+ MB$/.test(s.count));
  if (counted.length < 2) fail(`the loading bar showed no byte count over a slow line: ${JSON.stringify(loading.samples.slice(0, 5))}`);
  summary.loading = {
    rate_bytes_per_s: LOADING_RATE,
    first_count: counted[0],
    last_count: counted.at(-1),
    samples: loading.samples.length,
    first_frame_s: loading.first_frame_s,
  };
  writeFileSync(join(out, "console.log"), logs.join("\n"));
  writeFileSync(join(out, "browser.json"), JSON.stringify(summary, null, 1));
  console.log(`browser test: ${JSON.stringify(summary)}`);
} finally {
  await browser.close();
  server.kill();
}
