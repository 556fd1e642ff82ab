//! The native command-line planner (`cargo run --example plan`), run as a user runs it.

mod common;

use common::corpus::fields_dir;
use std::path::PathBuf;
use std::process::{Command, Output};

/// The example binary cargo built beside this test (`target/<profile>/examples/plan`).
fn plan_cli() -> Command {
    let exe = std::env::current_exe().expect("test executable");
    let dir = exe.parent().and_then(|d| d.parent()).expect("target dir");
    let bin: PathBuf = dir
        .join("examples")
        .join(format!("plan{}", std::env::consts::EXE_SUFFIX));
    assert!(bin.exists(), "{} not built", bin.display());
    Command::new(bin)
}

fn run(args: &[&str]) -> Output {
    plan_cli().args(args).output().expect("runs")
}

fn field(name: &str) -> String {
    fields_dir().join(name).display().to_string()
}

/// Runs the planner on `input` given on standard input (`-`).
fn run_on(input: &[u8], args: &[&str]) -> Output {
    use std::io::Write;
    let mut child = plan_cli()
        .arg("-")
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdin = child.stdin.take().expect("stdin");
    // The planner may refuse before reading everything: a broken pipe is no failure here.
    let _ = stdin.write_all(input);
    drop(stdin);
    child.wait_with_output().expect("finishes")
}

/// The code of the one JSON line on standard error.
fn error_code(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let e: serde_json::Value = serde_json::from_str(&stderr).expect("a JSON line");
    e["code"].as_str().expect("code").to_string()
}

/// A 300 m by 150 m rectangle at 60.25 N, its corner at 24.05 E.
fn rectangle_300_by_150() -> String {
    // 300 m of longitude and 150 m of latitude there (the planner's projection gives the same).
    let (east, north) = (24.055430963107863, 60.25134746676249);
    format!(
        r#"{{"type":"Polygon","coordinates":[[[24.05,60.25],[{east},60.25],[{east},{north}],[24.05,{north}],[24.05,60.25]]]}}"#
    )
}

#[test]
fn plans_the_rectangle_with_flags() {
    let out = run(&[
        &field("rectangle.geojson"),
        "--width",
        "6",
        "--headland-passes",
        "2",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).expect("GeoJSON on stdout");
    assert_eq!(plan["type"], "FeatureCollection");
    // 22 swaths across the inner field, and the fill of the four corners the passes round off.
    let fill = plan["summary"]["fill_swath_count"]
        .as_u64()
        .expect("a count");
    assert!((1..=8).contains(&fill), "{fill}");
    assert_eq!(plan["summary"]["swath_count"].as_u64(), Some(22 + fill));
    let swaths: Vec<&serde_json::Value> = plan["features"]
        .as_array()
        .expect("features")
        .iter()
        .filter(|f| f["properties"]["kind"] == "swath")
        .collect();
    assert_eq!(swaths.len() as u64, 22 + fill);
    let filling = swaths
        .iter()
        .filter(|f| f["properties"]["fill"] == true)
        .count();
    assert_eq!(filling as u64, fill);
}

#[test]
fn every_option_is_a_flag() {
    // Flags become the options object JavaScript passes: each option in kebab-case is accepted.
    let out = run(&[
        &field("square-1ha.geojson"),
        "--width=2.5",
        "--headland-passes",
        "3",
        "--turn-radius",
        "2.1",
        "--bearing",
        "30",
        "--min-swath-length",
        "4",
        "--coordinates",
        "wgs84",
        "--forbidden-bearings",
        "[[80,100]]",
        "--summary",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!((summary["bearing_deg"].as_f64().expect("bearing") - 30.0).abs() < 1e-9);
    // --help lists each of them.
    let help = String::from_utf8(run(&["--help"]).stdout).expect("utf8");
    for (key, _, _) in furrow::options::OPTION_DOCS {
        let flag: String = key
            .chars()
            .flat_map(|c| {
                if c.is_uppercase() {
                    vec!['-', c.to_ascii_lowercase()]
                } else {
                    vec![c]
                }
            })
            .collect();
        assert!(
            help.contains(&format!("--{flag}")),
            "--{flag} missing from --help"
        );
    }
}

#[test]
fn invalid_input_exits_2_with_one_json_line() {
    for (file, code) in [
        (
            "invalid/self-intersecting-bowtie.geojson",
            "self_intersection",
        ),
        ("invalid/not-geojson.geojson", "invalid_json"),
    ] {
        let out = run(&[&field(file)]);
        assert_eq!(out.status.code(), Some(2), "{file}");
        let stderr = String::from_utf8(out.stderr).expect("utf8");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        let e: serde_json::Value = serde_json::from_str(&stderr).expect("JSON line");
        assert_eq!(e["code"], code);
        assert!(e["message"].as_str().is_some_and(|m| !m.is_empty()));
        assert!(out.stdout.is_empty());
    }
    let out = run(&[&field("rectangle.geojson"), "--widht", "6"]);
    assert_eq!(out.status.code(), Some(2));
    let e: serde_json::Value = serde_json::from_slice(&out.stderr).expect("JSON line");
    assert_eq!(e["code"], "invalid_option");
    assert!(e["message"].as_str().expect("message").contains("--widht"));
    let out = run(&[&field("rectangle.geojson"), "--width", "-2"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn writes_to_a_file_and_reads_standard_input() {
    let dir = std::env::temp_dir().join(format!("furrow-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("plan.geojson");
    let out = run(&[
        &field("l-shape.geojson"),
        "--out",
        &path.display().to_string(),
    ]);
    assert!(out.status.success());
    assert!(out.stdout.is_empty());
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("written")).expect("JSON");
    assert_eq!(written["type"], "FeatureCollection");
    std::fs::remove_dir_all(&dir).ok();

    use std::io::Write;
    let mut child = plan_cli()
        .args(["-", "--summary"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("spawns");
    let text = std::fs::read(fields_dir().join("square-1ha.geojson")).expect("field");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(&text)
        .expect("writes");
    let out = child.wait_with_output().expect("finishes");
    assert!(out.status.success());
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!(summary["swath_count"].as_u64().expect("count") > 0);
}

#[test]
fn a_missing_file_exits_1() {
    let out = run(&["/nonexistent/field.geojson"]);
    assert_eq!(out.status.code(), Some(1));
    let e: serde_json::Value = serde_json::from_slice(&out.stderr).expect("JSON line");
    assert_eq!(e["code"], "io_error");
}

#[test]
fn prints_the_shortest_path_along_the_tracks() {
    // The rectangle's corner (24.05, 60.25); from a point inside, facing north.
    let args = |turning: &str| {
        run(&[
            &field("rectangle.geojson"),
            "--width",
            "6",
            "--headland-passes",
            "2",
            "--turn-radius",
            "8",
            "--from",
            "24.0515,60.2508",
            "--heading",
            "0",
            "--to",
            "24.05,60.25",
            "--turning",
            turning,
        ])
    };
    let mut lengths = Vec::new();
    for turning in ["on-the-spot", "heading", "tracks"] {
        let out = args(turning);
        if turning == "tracks" && out.status.code() == Some(2) {
            // Only tracks as driven: where the coverage path leads away, there may be no way.
            assert!(String::from_utf8_lossy(&out.stderr).contains("\"no_path\""));
            continue;
        }
        assert!(
            out.status.success(),
            "{turning}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let path: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a Feature");
        assert_eq!(path["type"], "Feature");
        assert_eq!(path["geometry"]["type"], "LineString");
        assert_eq!(path["properties"]["turning"], turning);
        let length = path["properties"]["length_m"].as_f64().expect("length_m");
        let coords = path["geometry"]["coordinates"]
            .as_array()
            .expect("coordinates");
        let last = coords
            .last()
            .and_then(|c| c.as_array())
            .expect("a position");
        // It ends on the boundary lane, near the corner (the lane runs w/2 inside the edge).
        let (lon, lat) = (
            last[0].as_f64().unwrap_or(0.0),
            last[1].as_f64().unwrap_or(0.0),
        );
        assert!(
            (lon - 24.05).abs() < 1e-4 && (lat - 60.25).abs() < 1e-4,
            "{lon}, {lat}"
        );
        lengths.push(length);
    }
    assert!(lengths.windows(2).all(|w| w[0] <= w[1]), "{lengths:?}");
    // Errors: a start far from the tracks, an unknown turning, a missing --to.
    let refused = |extra: &[&str], code: &str| {
        let rect = field("rectangle.geojson");
        let mut args = vec![rect.as_str()];
        args.extend_from_slice(extra);
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(&format!("\"{code}\"")),
            "{extra:?}: {stderr}"
        );
    };
    let from = ["--from", "24.0515,60.2508", "--heading", "0"];
    refused(
        &[
            "--from",
            "24.2,60.5",
            "--heading",
            "0",
            "--to",
            "24.05,60.25",
        ],
        "off_tracks",
    );
    refused(
        &[&from[..], &["--to", "24.05,60.25", "--turning", "sideways"]].concat(),
        "invalid_option",
    );
    refused(&from, "usage");
}

#[test]
fn a_field_saved_with_an_entrance_and_ab_line_plans_with_them() {
    // As the viewer saves a field: the entrance and the AB line at the end of the features.
    let dir = std::env::temp_dir().join(format!("furrow-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("saved.geojson");
    std::fs::write(
        &path,
        r#"{"type":"FeatureCollection","features":[
        {"type":"Feature","properties":{"role":"boundary"},"geometry":{"type":"Polygon","coordinates":[[[24.05,60.25],[24.056,60.25],[24.056,60.252],[24.05,60.252],[24.05,60.25]]]}},
        {"type":"Feature","properties":{"role":"entrance"},"geometry":{"type":"Point","coordinates":[24.056,60.251]}},
        {"type":"Feature","properties":{"role":"reference_line"},"geometry":{"type":"LineString","coordinates":[[24.05,60.25],[24.056,60.252]]}}]}"#,
    )
    .expect("written");
    let file = path.display().to_string();
    let out = run(&[&file]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a plan");
    assert_eq!(
        plan["summary"]["direction"]["mode"], "reference",
        "along the AB line"
    );
    let warnings = plan["warnings"].as_array().expect("warnings");
    assert!(
        warnings.iter().all(|w| w["code"] != "ignored_feature"),
        "nothing ignored: {warnings:?}"
    );
    let first = plan["features"]
        .as_array()
        .and_then(|f| f.iter().find(|f| f["properties"]["sequence"] == 0))
        .expect("the first drivable feature");
    assert_eq!(
        first["properties"]["kind"], "connection",
        "from the entrance"
    );
    assert_eq!(
        first["geometry"]["coordinates"][0],
        serde_json::json!([24.056, 60.251])
    );
    // Options still win: a bearing given on the command line.
    let out = run(&[&file, "--bearing", "0"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a plan");
    assert_eq!(plan["summary"]["direction"]["mode"], "fixed");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn forbidden_bearings_all_the_way_round_forbid_every_direction() {
    let field = rectangle_300_by_150();
    let out = run_on(
        field.as_bytes(),
        &["--forbidden-bearings", "[[0,90]]", "--summary"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for all in ["[[0,180]]", "[[0,360]]", "[[-90,270]]", "[[0,720]]"] {
        let out = run_on(
            field.as_bytes(),
            &["--forbidden-bearings", all, "--summary"],
        );
        assert_eq!(out.status.code(), Some(2), "{all}");
        assert_eq!(error_code(&out), "no_allowed_direction", "{all}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn options_past_any_sense_exit_2() {
    let field = rectangle_300_by_150();
    for (flag, value) in [
        ("--entrance", "[1e300,1e300]"),
        ("--exit", "[24.05,60.45]"),
        ("--working-speed", "1e-320"),
        ("--turning-speed", "0.01"),
    ] {
        let out = run_on(field.as_bytes(), &[flag, value, "--summary"]);
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        assert_eq!(error_code(&out), "option_out_of_range", "{flag} {value}");
    }
}

#[test]
fn input_that_is_not_utf8_exits_2() {
    // The fourth line's text holds a byte that UTF-8 never has.
    let mut input = rectangle_300_by_150().into_bytes();
    let at = input.len() - 1;
    input.splice(at..at, b",\n\"name\":\n\n\"F\xffeld\"".iter().copied());
    let check = |out: Output| {
        assert_eq!(out.status.code(), Some(2));
        assert_eq!(error_code(&out), "invalid_json");
        let e: serde_json::Value = serde_json::from_slice(&out.stderr).expect("JSON line");
        assert_eq!(
            (e["line"].as_u64(), e["column"].as_u64()),
            (Some(4), Some(3))
        );
        assert!(e["message"].as_str().is_some_and(|m| m.contains("UTF-8")));
    };
    check(run_on(&input, &[]));
    let dir = std::env::temp_dir().join(format!("furrow-cli-utf8-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("latin1.geojson");
    std::fs::write(&path, &input).expect("written");
    check(run(&[&path.display().to_string()]));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn input_over_32_mb_is_refused_unread() {
    let limit = furrow::field::geojson::MAX_INPUT_BYTES;
    // Standard input: twice the limit, and the planner stops reading after the limit, so the
    // rest cannot be written (the pipe is closed on it).
    let mut input = rectangle_300_by_150().into_bytes();
    input.resize(2 * limit, b' ');
    let mut child = plan_cli()
        .arg("-")
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || {
        use std::io::Write;
        stdin.write_all(&input)
    });
    let out = child.wait_with_output().expect("finishes");
    let written = writer.join().expect("the writer");
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(error_code(&out), "input_too_large");
    assert_eq!(
        written.map_err(|e| e.kind()),
        Err(std::io::ErrorKind::BrokenPipe),
        "the planner read all the input"
    );
    // A file says its size: a sparse one larger than any field file is refused by it; one of
    // 33 MB that is not a zip archive is refused as GeoJSON over its limit.
    let dir = std::env::temp_dir().join(format!("furrow-cli-large-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("large.geojson");
    for size in [
        furrow::formats::MAX_FILE_BYTES as u64 + 1,
        limit as u64 + 1024 * 1024,
    ] {
        let file = std::fs::File::create(&path).expect("created");
        file.set_len(size).expect("sized");
        let out = run(&[&path.display().to_string()]);
        assert_eq!(out.status.code(), Some(2));
        assert_eq!(error_code(&out), "input_too_large");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A register's export as a zipped Shapefile (RD New, `scripts/format-fixtures.sh`).
fn shapefile_fixture() -> String {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/format-fixtures/nl_brp_rd_new.zip"
    )
    .to_string()
}

#[test]
fn a_zipped_shapefile_of_several_parcels_plans_the_one_picked() {
    let zip = shapefile_fixture();
    // Its 53 parcels as GeoJSON in WGS84.
    let out = run(&[&zip, "--field-only"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let field: serde_json::Value = serde_json::from_slice(&out.stdout).expect("GeoJSON");
    assert_eq!(field["features"].as_array().map(Vec::len), Some(53));
    assert_eq!(field["source"]["crs"], "EPSG:28992 (Amersfoort / RD New)");
    // Planned without a pick: which one?
    let out = run(&[&zip, "--summary"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(error_code(&out), "ambiguous_boundary");
    // The first parcel picked plans, where the register has it (near 4.58 E, 52.12 N).
    let out = run(&[&zip, "--parcel", "0", "--width", "6"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a plan");
    assert!(plan["summary"]["swath_count"].as_u64().unwrap_or(0) > 0);
    let first = &plan["features"][0]["geometry"]["coordinates"];
    let text = first.to_string();
    assert!(text.contains("[4.57") && text.contains(",52.11"), "{text}");
    // A parcel the file does not have.
    let out = run(&[&zip, "--parcel", "53"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(error_code(&out), "usage");
}

#[test]
fn a_cut_zip_exits_2_with_invalid_file() {
    let bytes = std::fs::read(shapefile_fixture()).expect("fixture");
    let out = run_on(&bytes[..bytes.len() / 2], &["--summary"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(error_code(&out), "invalid_file");
}

/// The middle of `rectangle.geojson` and its south-west corner.
const RECTANGLE_MIDDLE: &str = "24.0522654435,60.2506744905";
const RECTANGLE_SOUTH_WEST: &str = "24.05,60.25";

#[test]
fn a_way_out_is_found_without_a_turning_option() {
    // From the middle of the rectangle facing north to its south-west corner: without turning
    // on the spot there is a way; only along tracks as driven there is none.
    let rect = field("rectangle.geojson");
    let args = [
        rect.as_str(),
        "--from",
        RECTANGLE_MIDDLE,
        "--heading",
        "0",
        "--to",
        RECTANGLE_SOUTH_WEST,
    ];
    let out = run(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let path: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a Feature");
    assert_eq!(path["properties"]["turning"], "heading");
    assert!(path["properties"]["length_m"]
        .as_f64()
        .is_some_and(|l| l > 0.0));
    let strict = run(&[&args[..], &["--turning", "tracks"]].concat());
    assert_eq!(error_code(&strict), "no_path");
}

/// The plan's features (the summary holds the time planning took, which varies).
fn plan_features(args: &[&str]) -> serde_json::Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a plan");
    plan["features"].clone()
}

#[test]
fn positions_are_written_x_comma_y_or_in_json() {
    let rect = field("rectangle.geojson");
    let comma = plan_features(&[
        &rect,
        "--entrance",
        "24.0545,60.2507",
        "--exit",
        "24.05,60.2513",
        "--reference-line",
        "24.05,60.25,24.0545,60.2513",
    ]);
    let json = plan_features(&[
        &rect,
        "--entrance",
        "[24.0545,60.2507]",
        "--exit",
        "[24.05,60.2513]",
        "--reference-line",
        "[[24.05,60.25],[24.0545,60.2513]]",
    ]);
    assert_eq!(comma, json);
    // The route starts at the entrance.
    let first = comma
        .as_array()
        .and_then(|f| f.iter().find(|f| f["properties"]["sequence"] == 0))
        .expect("the first drivable feature");
    assert_eq!(
        first["geometry"]["coordinates"][0],
        serde_json::json!([24.0545, 60.2507])
    );
    // What is neither is refused, saying the form.
    for (flag, value) in [
        ("--entrance", "24.05"),
        ("--exit", "24.05;60.25"),
        ("--reference-line", "24.05,60.25"),
    ] {
        let out = run(&[&rect, flag, value]);
        assert_eq!(error_code(&out), "invalid_option", "{flag} {value}");
        let e: serde_json::Value = serde_json::from_slice(&out.stderr).expect("JSON line");
        assert!(
            e["message"].as_str().is_some_and(|m| m.contains("x,y")),
            "{e}"
        );
    }
}

#[test]
fn an_option_without_its_value_says_so() {
    let rect = field("rectangle.geojson");
    for args in [
        vec![rect.as_str(), "--width"],
        vec![rect.as_str(), "--width", "--summary"],
        vec![rect.as_str(), "--entrance"],
        vec![rect.as_str(), "--turn-radius", "--summary"],
    ] {
        let out = run(&args);
        assert_eq!(error_code(&out), "invalid_option", "{args:?}");
        let e: serde_json::Value = serde_json::from_slice(&out.stderr).expect("JSON line");
        let message = e["message"].as_str().expect("message");
        assert!(message.contains("needs a value"), "{message}");
        assert!(!message.contains("true"), "{message}");
    }
    // A yes-or-no option needs none, and leaves the field after it alone.
    let out = run(&["--reverse", &rect, "--summary"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The words of a shell command as the README writes them: plain words, '...' and "...".
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote = None;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, c) => {
                assert!(
                    !"|<>;&$`*?#".contains(c),
                    "README command with shell syntax ({c}): {line}"
                );
                word.get_or_insert_with(String::new).push(c);
            }
        }
    }
    assert!(quote.is_none(), "unclosed quote: {line}");
    words.extend(word);
    words
}

/// The arguments of every command-line example in the README's `sh` blocks.
fn readme_cli_examples() -> Vec<Vec<String>> {
    const CLI: &str = "cargo run --release --example plan --";
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("README.md");
    let mut commands = Vec::new();
    let (mut in_sh, mut command) = (false, String::new());
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = line == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        command.push_str(line.trim_end_matches('\\'));
        if line.ends_with('\\') {
            command.push(' ');
            continue;
        }
        if let Some(args) = command.trim().strip_prefix(CLI) {
            commands.push(shell_words(args));
        }
        command.clear();
    }
    commands
}

#[test]
fn the_readme_cli_examples_run() {
    let commands = readme_cli_examples();
    assert!(commands.len() >= 3, "{commands:?}");
    for args in commands {
        let out = plan_cli()
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(&args)
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        assert!(json.is_object(), "{args:?}");
    }
}

#[test]
fn the_plan_goes_to_an_isobus_terminal_as_zipped_isoxml() {
    let dir = std::env::temp_dir().join(format!("furrow-cli-isoxml-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let zip = dir.join("taskdata.zip");
    let out = run(&[
        &field("l-shape.geojson"),
        "--width",
        "6",
        "--format",
        "isoxml",
        "--out",
        &zip.display().to_string(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Unpacked by Python's zipfile, another reader than furrow's.
    let script = "import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); print(z.namelist()); sys.stdout.write(z.read('TASKDATA/TASKDATA.XML').decode())";
    let read = Command::new("python3")
        .args(["-c", script, &zip.display().to_string()])
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&read.stdout);
    assert!(text.starts_with("['TASKDATA/TASKDATA.XML']"), "{text}");
    assert!(text.contains(r#"<ISO11783_TaskData VersionMajor="4""#));
    assert!(text.contains(r#"<PFD A="PFD1""#) && text.contains(r#"<GGP A="GGP1" B="Block 1">"#));
    // KML for Google Earth, on standard output.
    let out = run(&[&field("l-shape.geojson"), "--format", "kml"]);
    assert!(out.status.success());
    let kml = String::from_utf8_lossy(&out.stdout);
    assert!(kml.starts_with("<?xml") && kml.contains("<Folder><name>Swaths</name>"));
    // Version 3, and a format it does not write.
    let out = run(&[&field("l-shape.geojson"), "--format", "isoxml-v3"]);
    assert!(out.status.success());
    let out = run(&[&field("l-shape.geojson"), "--format", "shapefile"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(error_code(&out), "usage");
    let _ = std::fs::remove_dir_all(&dir);
}
