// A small static file server for the viewer (no dependencies): serves a directory on localhost
// with the right MIME types (WebAssembly must be application/wasm) and no caching.
//
//   node scripts/serve.mjs [--root target/site] [--port 8080] [--host 127.0.0.1]
//
// Also imported by the browser tests: startServer(root, port) resolves to the listening server.
// Every response carries the page's Content-Security-Policy (index.html's meta tag, plus
// frame-ancestors); a request that is not a plain path gets 400, and no error's text is sent.
import { createServer } from "node:http";
import { readFile, stat } from "node:fs/promises";
import { extname, join, normalize, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";

const TYPES = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".mjs": "text/javascript; charset=utf-8",
  ".css": "text/css; charset=utf-8",
  ".json": "application/json; charset=utf-8",
  ".geojson": "application/geo+json; charset=utf-8",
  ".wasm": "application/wasm",
  ".svg": "image/svg+xml",
  ".png": "image/png",
  ".ico": "image/x-icon",
  ".webmanifest": "application/manifest+json",
  ".txt": "text/plain; charset=utf-8",
  ".md": "text/plain; charset=utf-8",
  ".ts": "text/plain; charset=utf-8",
};

/**
 * The path a request asks for, decoded, or null when the request target is not a plain path
 * (an absolute URL, "//" and the like, a malformed %-escape, a NUL).
 */
export function requestPath(target) {
  const raw = String(target ?? "").split(/[?#]/, 1)[0];
  if (!/^\/(?!\/)/.test(raw)) return null;
  let path;
  try {
    path = decodeURIComponent(raw);
  } catch {
    return null;
  }
  return path.includes("\0") ? null : path;
}

/** The Content-Security-Policy of a page's `<meta http-equiv>`, or null. */
export function metaPolicy(html) {
  const meta = /<meta\s+http-equiv="Content-Security-Policy"\s+content="([^"]*)"/i.exec(html);
  return meta ? meta[1].replace(/&#39;|&apos;/g, "'").trim() : null;
}

/**
 * The policy the server sends with every response: the page's own (index.html's meta tag, so
 * that the two never differ), with `frame-ancestors`, which only a header can carry.
 */
async function headerPolicy(base) {
  const html = await readFile(join(base, "index.html"), "utf8").catch(() => "");
  const policy = metaPolicy(html);
  return policy ? `${policy.replace(/;\s*$/, "")}; frame-ancestors 'none'` : null;
}

export async function startServer(root, port = 8080, host = "127.0.0.1") {
  const base = resolve(root);
  const policy = await headerPolicy(base);
  const security = {
    ...(policy ? { "content-security-policy": policy } : {}),
    "x-content-type-options": "nosniff",
    "referrer-policy": "no-referrer",
  };
  const answer = (res, status, text) =>
    res.writeHead(status, { ...security, "content-type": "text/plain; charset=utf-8" }).end(text);
  const server = createServer(async (req, res) => {
    try {
      const asked = requestPath(req.url);
      if (asked == null) {
        answer(res, 400, "bad request");
        return;
      }
      let path = normalize(join(base, asked));
      if (path !== base && !path.startsWith(base + sep)) {
        answer(res, 403, "forbidden");
        return;
      }
      let info = await stat(path).catch(() => null);
      if (info?.isDirectory()) {
        path = join(path, "index.html");
        info = await stat(path).catch(() => null);
      }
      if (!info && asked === "/favicon.ico") {
        res.writeHead(204, security).end(); // browsers ask for it on any page; not an error
        return;
      }
      if (!info) {
        answer(res, 404, "not found");
        return;
      }
      const body = await readFile(path);
      res.writeHead(200, {
        ...security,
        "content-type": TYPES[extname(path).toLowerCase()] ?? "application/octet-stream",
        "cache-control": "no-store",
      });
      res.end(req.method === "HEAD" ? undefined : body);
    } catch (e) {
      // What went wrong is the server's to know, not the client's.
      console.error(`serve: ${req.method} ${JSON.stringify(req.url)}: ${e?.stack ?? e}`);
      if (!res.headersSent) answer(res, 500, "internal error");
      else res.destroy();
    }
  });
  return new Promise((ok, fail) => {
    server.once("error", fail);
    server.listen(port, host, () => ok(server));
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const arg = (name, fallback) => {
    const i = process.argv.indexOf(`--${name}`);
    return i > 0 && process.argv[i + 1] ? process.argv[i + 1] : fallback;
  };
  const root = arg("root", "target/site");
  const port = Number(arg("port", "8080"));
  const host = arg("host", "127.0.0.1");
  startServer(root, port, host).then(
    (server) => {
      const { port: p } = server.address();
      console.log(`furrow viewer: http://localhost:${p}/  (serving ${root}; Ctrl-C to stop)`);
    },
    (e) => {
      console.error(e.code === "EADDRINUSE" ? `port ${port} is in use: try --port 8081` : String(e));
      process.exit(1);
    },
  );
}
