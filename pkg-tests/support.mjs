// Shared by the browser tests: Debian's Chromium through playwright-core (never a downloaded
// browser), and the assembled site they serve.
import { execFileSync } from "node:child_process";
import { join } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

export const ROOT = fileURLToPath(new URL("..", import.meta.url));
export const SITE = join(ROOT, "target/site");

// Without the background-networking flags Chromium keeps trying hosts this machine cannot reach.
const ARGS = [
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];

/** Debian's chromium, or the binary CHROMIUM names. */
export function chromiumPath() {
  if (process.env.CHROMIUM) return process.env.CHROMIUM;
  try {
    return execFileSync("which", ["chromium"], { encoding: "utf8" }).trim();
  } catch {
    throw new Error("chromium not found: apt-get install chromium (or set CHROMIUM=/path/to/chrome)");
  }
}

/** A headless Chromium. */
export function launchChromium() {
  return chromium.launch({ executablePath: chromiumPath(), headless: true, args: ARGS });
}
