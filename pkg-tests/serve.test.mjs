// The viewer's dev server (scripts/serve.mjs), in Node: bad request targets get 400 and no
// exception's text; every response carries the page's Content-Security-Policy.
//
//   node --test pkg-tests/serve.test.mjs   (after scripts/build.sh: it serves target/site)
import { test } from "node:test";
import assert from "node:assert/strict";
import { request } from "node:http";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { metaPolicy, requestPath, startServer } from "../scripts/serve.mjs";
import { ROOT, SITE } from "./support.mjs";

/** A raw GET of `target` exactly as written (no client-side normalising): { status, headers, body }. */
function get(port, target) {
  return new Promise((ok, fail) => {
    const req = request({ host: "127.0.0.1", port, path: target, method: "GET" }, (res) => {
      let body = "";
      res.setEncoding("utf8");
      res.on("data", (d) => (body += d));
      res.on("end", () => ok({ status: res.statusCode, headers: res.headers, body }));
    });
    req.on("error", fail);
    req.end();
  });
}

test("requestPath: plain paths decoded; anything else null", () => {
  assert.equal(requestPath("/"), "/");
  assert.equal(requestPath("/fields/a%20b.geojson?x=1#y"), "/fields/a b.geojson");
  assert.equal(requestPath("/a//b"), "/a//b");
  for (const bad of ["//", "//evil.example/x", "/%", "/%E0%A4%A", "/a%00b", "http://x/", "*", ""]) {
    assert.equal(requestPath(bad), null, JSON.stringify(bad));
  }
});

test("serve: bad request targets get 400 without an exception's text; files and 404s as before", async () => {
  const server = await startServer(SITE, 0);
  try {
    const { port } = server.address();
    for (const target of ["//", "/%", "/%E0%A4%A", "/fields/%zz.geojson", "/%00", "///etc/passwd"]) {
      const r = await get(port, target);
      assert.equal(r.status, 400, `${target}: ${r.status} ${r.body}`);
      assert.equal(r.body, "bad request", `${target}: the answer names no exception`);
    }
    assert.equal((await get(port, "/index.html")).status, 200);
    assert.equal((await get(port, "/fields/index.json")).status, 200);
    const missing = await get(port, "/no-such-file.js");
    assert.equal(missing.status, 404);
    assert.equal(missing.body, "not found");
    assert.equal((await get(port, "/..%2f..%2fetc/passwd")).status, 403);
  } finally {
    await new Promise((ok) => server.close(ok));
  }
});

test("serve: every response carries the page's Content-Security-Policy, and the site keeps the page's", async () => {
  const page = readFileSync(join(ROOT, "www/index.html"), "utf8");
  const policy = metaPolicy(page);
  assert.ok(policy, "www/index.html has a Content-Security-Policy meta tag");
  assert.match(policy, /default-src 'none'/);
  assert.match(policy, /script-src 'self' 'wasm-unsafe-eval'(;|$)/, "no inline scripts, no eval; WebAssembly may compile");
  assert.doesNotMatch(policy, /unsafe-inline|'unsafe-eval'|\*/, "nothing loosens it");
  assert.equal(metaPolicy(readFileSync(join(SITE, "index.html"), "utf8")), policy, "target/site/index.html has the same");
  const server = await startServer(SITE, 0);
  try {
    const { port } = server.address();
    for (const target of ["/", "/main.js", "/worker.js", "/sw.js", "/pkg/furrow_wasm_bg.wasm", "/nothing", "//"]) {
      const r = await get(port, target);
      assert.equal(r.headers["content-security-policy"], `${policy}; frame-ancestors 'none'`, target);
      assert.equal(r.headers["x-content-type-options"], "nosniff", target);
    }
  } finally {
    await new Promise((ok) => server.close(ok));
  }
});
