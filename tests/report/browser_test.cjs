// Opens an `impactfe report` page in headless Chromium (Debian's chromium, driven by
// playwright-core from the build's node_modules), with every network request refused. Fails on
// a console error, a page error, a network request, an empty plot or a 3-D view that drew
// nothing; writes a full-page screenshot and prints its path.
//
//   NODE_PATH=<build>/report_js/node_modules node browser_test.cjs REPORT.html OUTDIR [KIND]
//
// KIND `gaps` (default, the helmet): a gap status timeline and at least 6 plots; screenshots
// report_screenshot.png and report_3d_view.png. KIND `contact` (the plate drop): a contact-force
// figure per pair and the rigid floor drawn as an overlay; screenshots <stem>_screenshot.png
// and <stem>_3d_view.png.
'use strict';
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const { pathToFileURL } = require('node:url');

const FLAGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  // WebGL without a GPU: SwiftShader, which Chromium only enables on request.
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

async function main() {
  const [report, outDir, kind = 'gaps'] = process.argv.slice(2);
  if (kind !== 'gaps' && kind !== 'contact') throw new Error(`KIND '${kind}': gaps or contact`);
  const prefix = kind === 'gaps' ? 'report' : path.basename(report, '.html');
  if (!report || !outDir) throw new Error('usage: browser_test.cjs REPORT.html OUTDIR');
  const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
  if (!fs.existsSync(executablePath)) throw new Error(`no Chromium at ${executablePath} (scripts/install-deps.sh installs Debian's chromium)`);
  const { chromium } = require('playwright-core');
  fs.mkdirSync(outDir, { recursive: true });
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'impactfe-chromium-'));
  const problems = [];
  const context = await chromium.launchPersistentContext(profile, {
    executablePath,
    headless: true,
    args: FLAGS,
    viewport: { width: 1400, height: 1000 },
    deviceScaleFactor: 1,
  });
  try {
    await context.route('**/*', (route) => {
      const url = route.request().url();
      if (/^(file|data|blob):/.test(url)) return route.continue();
      problems.push(`network request: ${url}`);
      return route.abort();
    });
    const page = context.pages()[0] || (await context.newPage());
    page.on('console', (m) => {
      if (m.type() === 'error') problems.push(`console error: ${m.text()}`);
    });
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    await page.goto(pathToFileURL(path.resolve(report)).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.impactfeReport && window.impactfeReport.ready === true, null, { timeout: 60000 });
    const stats = await page.evaluate(() => window.impactfeReport.stats());
    const check = (ok, message) => {
      if (!ok) problems.push(message);
    };
    console.log(`plots: ${stats.plots.length}, 3-D: ${stats.triangles} triangles (mesh ${stats.meshTriangles}), ${stats.lines} lines, covered ${(100 * stats.coveredPixels).toFixed(1)} % of the view, ${stats.frames} frames, ${stats.gapRows} gap rows`);
    check(stats.errors.length === 0, `page errors: ${stats.errors.join('; ')}`);
    check(stats.webgl, 'the 3-D view has no WebGL context');
    check(stats.meshTriangles > 0 && stats.triangles >= stats.meshTriangles, `the 3-D view drew ${stats.triangles} triangles of ${stats.meshTriangles}`);
    check(stats.coveredPixels > 0.02, `the 3-D view covers ${(100 * stats.coveredPixels).toFixed(2)} % of its canvas (the helmet is not drawn)`);
    check(stats.plots.length >= (kind === 'gaps' ? 6 : 4), `only ${stats.plots.length} plots`);
    for (const p of stats.plots) {
      check(p.series.length > 0, `plot "${p.title}" has no curve`);
      for (const s of p.series) check(s.points > 1, `plot "${p.title}": curve "${s.label}" has ${s.points} points`);
      check(p.inkPixels > 100, `plot "${p.title}" drew ${p.inkPixels} curve pixels (empty plot)`);
      check(p.width > 300 && p.height > 200, `plot "${p.title}" is ${p.width} x ${p.height}`);
    }
    if (kind === 'gaps') check(stats.gapRows > 0, 'no gap status timeline');
    if (kind === 'contact') {
      check(stats.plots.some((p) => p.title.startsWith('Contact force of pair')), 'no contact-force figure');
      check(stats.overlayTriangles > 0, 'no target overlay in the 3-D view');
      check(stats.triangles >= stats.meshTriangles + stats.overlayTriangles, `the 3-D view drew ${stats.triangles} triangles, mesh and overlay have ${stats.meshTriangles + stats.overlayTriangles}`);
    }

    // The page as it opens (the 3-D view at the frame of the peak stress).
    const shot = path.join(outDir, `${prefix}_screenshot.png`);
    await page.screenshot({ path: shot, fullPage: true });

    // Move the time slider to the middle and colour by |U|: still drawn, no error.
    const after = await page.evaluate(() => {
      const v = window.impactfeReport.view;
      v.colourSelect.value = '|U|';
      v.show(Math.floor(v.times.length / 2));
      return { covered: v.coveredPixels(), label: v.timeLabel.textContent };
    });
    console.log(`slider: ${after.label}, covered ${(100 * after.covered).toFixed(1)} %`);
    check(after.covered > 0.02, 'the 3-D view is empty after moving the time slider');

    const viewShot = path.join(outDir, `${prefix}_3d_view.png`);
    await page.locator('.view3d').screenshot({ path: viewShot });
    console.log(`screenshot: ${shot}`);
    console.log(`3-D view screenshot: ${viewShot}`);
  } finally {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  if (problems.length) {
    for (const p of problems) console.log(`FAIL: ${p}`);
    console.log(`${problems.length} failed`);
    process.exit(1);
  }
  console.log('browser checks: ok');
}

main().catch((e) => {
  console.error(e && e.stack ? e.stack : e);
  process.exit(1);
});
