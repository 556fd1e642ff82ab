//! Every input within the documented caps (200,000 vertices, 32 MB of GeoJSON, 100,000 swaths)
//! plans, or is refused with a typed error, in bounded time and memory: worst cases made by code
//! (many obstacles, many holes, fine widths on noisy outlines, the most vertices, the most
//! swaths) and the reproducers that once took tens of seconds.
//!
//! A hang check, not a speed target: each case runs in a child process (this test binary again,
//! with `FURROW_TERMINATION_CASE` naming the case) that is killed after [`LIMIT`]; the test fails
//! if a case is killed, aborts, or ends in an `internal` error. Natively in release every case
//! takes a few seconds at most, in debug minutes: so the test is ignored in the regular suite and
//! scripts/test.sh runs it in release:
//!
//! ```text
//! cargo test --release --test termination -- --ignored
//! ```
//!
//! `FURROW_WORST_CASES=DIR cargo test --release --test termination -- --ignored write_cases`
//! writes each case's GeoJSON and command-line options to DIR, for measuring with the CLI.

use furrow::{plan_geojson, ErrorCode, PlanOptions};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a case may take before it counts as a hang.
const LIMIT: Duration = Duration::from_secs(60);

/// The most virtual memory a case's process may map (KiB): an allocation beyond it fails, and
/// the process aborts, rather than taking the machine's memory.
const MEMORY_LIMIT_KIB: u64 = 4 * 1024 * 1024;

/// The environment variable naming the case a child process runs.
const CASE_VAR: &str = "FURROW_TERMINATION_CASE";

/// One worst case: a field made by code and the options it is planned with (as JSON, the
/// JavaScript API's names).
struct Case {
    name: &'static str,
    field: fn() -> String,
    options: fn() -> Value,
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "obstacles_2000",
            field: || obstacle_grid(40, 50),
            options: || json!({"coordinates": "metric"}),
        },
        Case {
            name: "obstacles_2000_no_headland",
            field: || obstacle_grid(40, 50),
            options: || json!({"coordinates": "metric", "headlandPasses": 0}),
        },
        Case {
            name: "small_obstacles_5000",
            field: || small_obstacles(5_000, 12.0),
            options: || json!({"coordinates": "metric"}),
        },
        Case {
            name: "small_obstacles_10000",
            field: || small_obstacles(10_000, 12.0),
            options: || json!({"coordinates": "metric"}),
        },
        Case {
            name: "small_obstacles_49000",
            field: || small_obstacles(49_000, 5.5),
            options: || json!({"coordinates": "metric"}),
        },
        Case {
            name: "holes_1000",
            field: holes_field,
            options: || json!({"coordinates": "metric", "width": 3}),
        },
        Case {
            name: "star_5000_w0.2_none",
            field: || noisy_star(5_000, 150.0, 1.0, false),
            options: || json!({"coordinates": "metric", "width": 0.2, "decomposition": "none"}),
        },
        Case {
            name: "star_5000_w0.2",
            field: || noisy_star(5_000, 150.0, 1.0, false),
            options: || json!({"coordinates": "metric", "width": 0.2}),
        },
        Case {
            name: "star_5000_w0.1",
            field: || noisy_star(5_000, 150.0, 1.0, false),
            options: || json!({"coordinates": "metric", "width": 0.1}),
        },
        Case {
            name: "star_199000_w0.1",
            field: || noisy_star(199_000, 400.0, 0.5, true),
            options: || json!({"width": 0.1}),
        },
        Case {
            name: "star_199000",
            field: || noisy_star(199_000, 400.0, 0.5, true),
            options: || json!({}),
        },
        Case {
            name: "star_199000_needed",
            field: || noisy_star(199_000, 400.0, 0.5, true),
            options: || json!({"width": 1, "headlandMode": "needed"}),
        },
        Case {
            name: "gnss_199000",
            field: || gnss_trace(199_000, 2_000.0),
            options: || json!({}),
        },
        Case {
            name: "gnss_20000_needed_50",
            field: || gnss_trace(20_000, 200.0),
            options: || json!({"width": 0.1, "headlandMode": "needed", "headlandPasses": 50}),
        },
        Case {
            name: "gnss_20000_r2000_needed_50",
            field: || gnss_trace(20_000, 2_000.0),
            options: || json!({"width": 0.1, "headlandMode": "needed", "headlandPasses": 50}),
        },
        Case {
            name: "gnss_199000_w1",
            field: || gnss_trace(199_000, 2_000.0),
            options: || json!({"width": 1}),
        },
        Case {
            name: "disc_199000",
            field: || smooth_disc(199_000, 2_000.0),
            options: || json!({}),
        },
        Case {
            name: "disc_199000_w0.5",
            field: || smooth_disc(199_000, 2_000.0),
            options: || json!({"width": 0.5}),
        },
        Case {
            name: "star_199000_w0.1_no_headland",
            field: || noisy_star(199_000, 400.0, 0.5, true),
            options: || json!({"width": 0.1, "headlandPasses": 0}),
        },
        Case {
            name: "clothoid_1000km",
            field: || rectangle(200.0, 100.0),
            options: || json!({"coordinates": "metric", "turnRadius": 2, "curvatureRate": 5e-7}),
        },
        Case {
            name: "swaths_100000_short",
            field: || rectangle(9_990.0, 60.0),
            options: || json!({"coordinates": "metric", "width": 0.1, "bearing": 0}),
        },
        Case {
            name: "swaths_100000_long",
            field: || rectangle(9_990.0, 9_990.0),
            options: || json!({"coordinates": "metric", "width": 0.1, "bearing": 0}),
        },
        Case {
            name: "fuzz_101_3690",
            field: || reproducer("fuzz_101_3690"),
            options: || {
                json!({"width": 0.124, "headlandPasses": 0, "turnRadius": 0, "objective": "overlap",
                    "headlandMode": "needed", "headlandTolerance": 6.0, "headlandOrder": "last",
                    "workingSpeed": 1, "turningSpeed": 30})
            },
        },
        Case {
            name: "fuzz_103_1824",
            field: || reproducer("fuzz_103_1824"),
            options: || {
                json!({"width": 3.012, "headlandPasses": 0, "turnRadius": 100,
                    "objective": "swath-length", "reverse": true})
            },
        },
    ]
}

/// A field of `columns x rows` square obstacles 10 m across, 30 m apart, in local metres.
fn obstacle_grid(columns: usize, rows: usize) -> String {
    let (pitch, side, margin) = (30.0, 10.0, 40.0);
    let (w, h) = (
        2.0 * margin + pitch * columns as f64,
        2.0 * margin + pitch * rows as f64,
    );
    let mut features = vec![feature("boundary", &[rectangle_ring(0.0, 0.0, w, h)])];
    for i in 0..columns {
        for j in 0..rows {
            let (x, y) = (
                margin + pitch * i as f64 + 10.0,
                margin + pitch * j as f64 + 10.0,
            );
            features.push(feature(
                "obstacle",
                &[rectangle_ring(x, y, x + side, y + side)],
            ));
        }
    }
    collection(&features)
}

/// A 158 ha rectangle (1,580 x 1,000 m, local metres) with `count` small triangular obstacles
/// (0.5 m from centre to corner: class A at the default width) `pitch` metres apart, row by row
/// from 20 m inside the boundary.
fn small_obstacles(count: usize, pitch: f64) -> String {
    let (w, h, margin) = (1_580.0, 1_000.0, 20.0);
    let mut features = vec![feature("boundary", &[rectangle_ring(0.0, 0.0, w, h)])];
    let columns = ((w - 2.0 * margin) / pitch) as usize + 1;
    let rows = ((h - 2.0 * margin) / pitch) as usize + 1;
    let corners = [90.0f64, 210.0, 330.0].map(f64::to_radians);
    for k in 0..count.min(columns * rows) {
        let (x, y) = (
            margin + pitch * (k / rows) as f64,
            margin + pitch * (k % rows) as f64,
        );
        let mut ring: Vec<[f64; 2]> = corners
            .iter()
            .map(|a| [x + 0.5 * a.cos(), y + 0.5 * a.sin()])
            .collect();
        ring.push(ring[0]);
        features.push(feature("obstacle", &[ring]));
    }
    collection(&features)
}

/// A 2 km square field with 1,000 round holes of 96 vertices each (the boundary polygon's
/// interior rings), 4 to 20 m across, on a jittered grid: about 100,000 vertices.
fn holes_field() -> String {
    let mut rng = SplitMix(7);
    let side = 2_000.0;
    let mut rings = vec![rectangle_ring(0.0, 0.0, side, side)];
    for i in 0..40 {
        for j in 0..25 {
            let cx = 50.0 + 47.5 * i as f64 + 10.0 * rng.unit();
            let cy = 50.0 + 76.0 * j as f64 + 30.0 * rng.unit();
            let r = 2.0 + 8.0 * rng.unit();
            let mut ring: Vec<[f64; 2]> = (0..96)
                .map(|k| {
                    let t = k as f64 / 96.0 * std::f64::consts::TAU;
                    [cx + r * t.cos(), cy - r * t.sin()]
                })
                .collect();
            ring.push(ring[0]);
            rings.push(ring);
        }
    }
    collection(&[feature("boundary", &rings)])
}

/// A star of `vertices` points: radius `r` metres with seven arms of 30 %, each point moved
/// out or in at random by up to `noise` metres. In WGS84 near Helsinki, or local metres.
fn noisy_star(vertices: usize, r: f64, noise: f64, wgs84: bool) -> String {
    let mut rng = SplitMix(vertices as u64);
    let mut ring: Vec<[f64; 2]> = (0..vertices)
        .map(|k| {
            let t = k as f64 / vertices as f64 * std::f64::consts::TAU;
            let radius = r * (1.0 + 0.3 * (7.0 * t).sin()) + noise * (2.0 * rng.unit() - 1.0);
            [radius * t.cos(), radius * t.sin()]
        })
        .collect();
    ring.push(ring[0]);
    let ring = if wgs84 { to_wgs84(&ring) } else { ring };
    collection(&[feature("boundary", &[ring])])
}

/// A boundary recorded by a GNSS receiver as it might be: a seven-armed star of radius `r`
/// metres with `vertices` points, each off the true outline by an error that wanders (30 cm on
/// average, changing over about 5 m of driving), in WGS84.
fn gnss_trace(vertices: usize, r: f64) -> String {
    let mut rng = SplitMix(vertices as u64 + 1);
    let spacing = std::f64::consts::TAU * r / vertices as f64;
    let keep = (-spacing / 5.0).exp();
    let mut error = 0.0;
    let mut ring: Vec<[f64; 2]> = (0..vertices)
        .map(|k| {
            // A sum of four uniform numbers: near enough normal, 0.3 m across.
            let step = 0.3 * 1.2 * ((0..4).map(|_| rng.unit()).sum::<f64>() - 2.0);
            error = keep * error + (1.0 - keep * keep).sqrt() * step;
            let t = k as f64 / vertices as f64 * std::f64::consts::TAU;
            let radius = r * (1.0 + 0.3 * (7.0 * t).sin()) + error;
            [radius * t.cos(), radius * t.sin()]
        })
        .collect();
    ring.push(ring[0]);
    collection(&[feature("boundary", &[to_wgs84(&ring)])])
}

/// A disc of `vertices` points and radius `r` metres in WGS84.
fn smooth_disc(vertices: usize, r: f64) -> String {
    let mut ring: Vec<[f64; 2]> = (0..vertices)
        .map(|k| {
            let t = k as f64 / vertices as f64 * std::f64::consts::TAU;
            [r * t.cos(), r * t.sin()]
        })
        .collect();
    ring.push(ring[0]);
    collection(&[feature("boundary", &[to_wgs84(&ring)])])
}

/// A `w x h` metre rectangle in local metres.
fn rectangle(w: f64, h: f64) -> String {
    collection(&[feature("boundary", &[rectangle_ring(0.0, 0.0, w, h)])])
}

/// A reproducer kept in tests/fields/reproducers.
fn reproducer(name: &str) -> String {
    let path = format!(
        "{}/tests/fields/reproducers/{name}.geojson",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).expect("the reproducer is in tests/fields/reproducers")
}

/// Local metres around (0, 0) to longitude and latitude near Helsinki (60.2 N, 24.9 E), by the
/// local scale of a degree (near enough for a test field).
fn to_wgs84(ring: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let (lon0, lat0) = (24.9_f64, 60.2_f64);
    let per_lat = 111_320.0;
    let per_lon = per_lat * lat0.to_radians().cos();
    ring.iter()
        .map(|&[x, y]| [lon0 + x / per_lon, lat0 + y / per_lat])
        .collect()
}

fn rectangle_ring(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]
}

fn feature(role: &str, rings: &[Vec<[f64; 2]>]) -> String {
    let mut s = format!(
        r#"{{"type":"Feature","properties":{{"role":"{role}"}},"geometry":{{"type":"Polygon","coordinates":["#
    );
    for (i, ring) in rings.iter().enumerate() {
        s.push_str(if i == 0 { "[" } else { ",[" });
        for (k, [x, y]) in ring.iter().enumerate() {
            let _ = write!(s, "{}[{x},{y}]", if k == 0 { "" } else { "," });
        }
        s.push(']');
    }
    s.push_str("]}}");
    s
}

fn collection(features: &[String]) -> String {
    format!(
        r#"{{"type":"FeatureCollection","features":[{}]}}"#,
        features.join(",")
    )
}

/// SplitMix64: a small deterministic generator for the noise.
struct SplitMix(u64);

impl SplitMix {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The options of a case.
fn options_of(case: &Case) -> PlanOptions {
    serde_json::from_value((case.options)()).expect("the case's options are valid")
}

/// In a child process: plans the case `FURROW_TERMINATION_CASE` names and prints how it ended.
/// Does nothing when run on its own.
#[test]
#[ignore = "a child process of every_case_plans_or_is_refused_in_time"]
fn run_case() {
    let Ok(name) = std::env::var(CASE_VAR) else {
        return;
    };
    let case = cases()
        .into_iter()
        .find(|c| c.name == name)
        .expect("a known case");
    let text = (case.field)();
    let options = options_of(&case);
    let started = Instant::now();
    let outcome = plan_geojson(&text, &options);
    let ms = started.elapsed().as_secs_f64() * 1000.0;
    let outcome = outcome.map(|plan| {
        // What the JavaScript API returns besides: the GeoJSON and the samples.
        let text = plan.to_geojson_string();
        let samples = plan.samples();
        (plan, text.len(), samples.len())
    });
    let all_ms = started.elapsed().as_secs_f64() * 1000.0;
    match outcome {
        Ok((plan, text, samples)) => println!(
            "outcome {name}: planned in {ms:.0} ms ({all_ms:.0} ms with the GeoJSON and samples), peak memory {}: {} swaths, {} blocks, {} MB of GeoJSON, {samples} samples",
            peak_memory(),
            plan.summary.swath_count,
            plan.summary.block_count,
            text / 1_000_000,
        ),
        Err(e) => {
            assert_ne!(e.code, ErrorCode::Internal, "{name}: {}", e.message);
            println!(
                "outcome {name}: refused in {ms:.0} ms, peak memory {}: {}: {}",
                peak_memory(),
                e.code,
                e.message
            );
        }
    }
}

/// The process's peak resident memory, from Linux's /proc (the case's text and plan included).
fn peak_memory() -> String {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(format!("{} MB", kib / 1024))
        })
        .unwrap_or_else(|| "unknown".to_string())
}

/// Runs one case in a child process, killed after [`LIMIT`]: how it ended, and its time.
fn run_in_child(name: &str) -> Result<(String, Duration), String> {
    let exe = std::env::current_exe().expect("the test binary");
    let mut command = if cfg!(unix) {
        // The memory limit through the shell, which has it built in.
        let mut c = Command::new("sh");
        c.arg("-c")
            .arg(format!(
                "ulimit -v {MEMORY_LIMIT_KIB} && exec \"$0\" \"$@\""
            ))
            .arg(exe);
        c
    } else {
        Command::new(exe)
    };
    command
        .args(["run_case", "--exact", "--ignored", "--nocapture"])
        .env(CASE_VAR, name)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let started = Instant::now();
    let mut child = command.spawn().expect("the test binary runs");
    loop {
        if let Some(status) = child.try_wait().expect("the child's status") {
            let elapsed = started.elapsed();
            let output = child.wait_with_output().expect("the child's output");
            let stdout = String::from_utf8_lossy(&output.stdout);
            let line = stdout
                .lines()
                .find(|l| l.starts_with("outcome "))
                .map(str::to_string);
            return match (status.success(), line) {
                (true, Some(line)) => Ok((line, elapsed)),
                _ => Err(format!(
                    "{name} failed ({status}):\n{stdout}\n{}",
                    String::from_utf8_lossy(&output.stderr)
                )),
            };
        }
        if started.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("{name} still planning after {LIMIT:?}: killed"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
#[ignore = "minutes in debug; scripts/test.sh runs it in release"]
fn every_case_plans_or_is_refused_in_time() {
    let mut failures = Vec::new();
    for case in cases() {
        match run_in_child(case.name) {
            Ok((line, elapsed)) => eprintln!("{:>7.2} s  {line}", elapsed.as_secs_f64()),
            Err(e) => {
                eprintln!("{e}");
                failures.push(case.name);
            }
        }
    }
    assert!(failures.is_empty(), "cases that failed: {failures:?}");
}

/// Writes each case's GeoJSON (`NAME.geojson`) and its options as command-line flags
/// (`NAME.args`) and as JSON (`NAME.json`) to the directory `FURROW_WORST_CASES` names.
#[test]
#[ignore = "writes files for measuring with the CLI"]
fn write_cases() {
    let Ok(dir) = std::env::var("FURROW_WORST_CASES") else {
        return;
    };
    std::fs::create_dir_all(&dir).expect("the directory");
    for case in cases() {
        let path = |ext: &str| std::path::Path::new(&dir).join(format!("{}.{ext}", case.name));
        std::fs::write(path("geojson"), (case.field)()).expect("written");
        let mut flags = String::new();
        if let Value::Object(map) = (case.options)() {
            for (key, value) in map {
                let flag: String = key
                    .chars()
                    .flat_map(|c| {
                        let lower = c.to_ascii_lowercase();
                        (c.is_ascii_uppercase())
                            .then_some('-')
                            .into_iter()
                            .chain([lower])
                    })
                    .collect();
                let value = match value {
                    Value::String(s) => s,
                    v => v.to_string(),
                };
                let _ = write!(flags, "--{flag}={value} ");
            }
        }
        std::fs::write(path("args"), flags.trim_end()).expect("written");
        std::fs::write(path("json"), (case.options)().to_string()).expect("written");
    }
}
