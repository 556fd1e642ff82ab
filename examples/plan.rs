//! The native command-line planner.
//!
//! ```text
//! cargo run --release --example plan -- FIELD.geojson [--width M] [--headland-passes N]
//!     [--turn-radius M] [--bearing DEG] [... every planner option ...] [--out PLAN.geojson]
//! ```
//!
//! Every option of the JavaScript API is a flag here, its name in kebab-case (`headlandPasses`
//! is `--headland-passes`): flags are turned into the same options object JavaScript passes, so a
//! new option is a new flag without any change to this file. `FIELD` may be `-` for standard
//! input. The plan (GeoJSON) goes to standard output unless `--out` names a file.
//!
//! `FIELD` may also be a zipped Shapefile (`.zip` with `.shp`, `.shx`, `.dbf`, `.prj`), read and
//! converted to WGS84 by `furrow::formats`, KML or KMZ, or ISOXML TaskData (`TASKDATA.XML`
//! or its zip). A file of several parcels (a register's export, as
//! a Shapefile or GeoJSON) is planned one parcel at a time: `--parcel INDEX` picks one (0 for
//! the first). `--field-only` prints the field as read (GeoJSON, all its parcels or the one
//! picked) instead of planning it.
//!
//! `--format kml` writes the plan as KML for Google Earth; `--format isoxml` (or `isoxml-v3`)
//! writes it as ISOXML TaskData for an ISOBUS terminal,
//! zipped as `TASKDATA/TASKDATA.XML` (`--curves-as-ab`: the headland passes as AB segments).
//!
//! With `--from LON,LAT --heading DEG --to LON,LAT` it prints, instead of the plan, the shortest
//! way along the plan's tracks from there to the nearest point of the boundary lane to `--to`
//! (repeat `--to` for several exits; the nearest wins): a GeoJSON Feature with its `length_m`.
//! `--turning heading|tracks|on-the-spot` says how the machine may turn (default `heading`: no
//! turning on the spot; see the README).
//!
//! Positions are `x,y` (longitude,latitude) everywhere: `--entrance 24.05,60.25`, and the AB line
//! `--reference-line 24.05,60.25,24.056,60.252` (A then B); the JSON form (`[24.05,60.25]`) works
//! too.
//!
//! Exit status: 0 with a plan; 2 when the input or an option is invalid (the input too large or
//! not UTF-8 text too), with one line of JSON `{"code": ..., "message": ...}` on standard error;
//! 1 when a file cannot be read or written.

#![allow(clippy::result_large_err)] // the error path of a command-line tool

use furrow::field::geojson::MAX_INPUT_BYTES;
use furrow::formats::isoxml::{taskdata_zip, TaskDataSettings, TaskDataVersion};
use furrow::formats::plan_kml::plan_kml;
use furrow::formats::{is_field_file, read_field_file, MAX_FILE_BYTES};
use furrow::options::OPTION_DOCS;
use furrow::tracks::{PlanTracks, Turning};
use furrow::{plan_geojson, ErrorCode, PlanError, PlanOptions};
use serde_json::{Map, Value};
use std::io::{Read, Write};
use std::process::ExitCode;

const USAGE: &str =
    "usage: plan FIELD.geojson|.zip|.kml|.kmz [--parcel INDEX] [--OPTION VALUE ...] [--out PLAN.geojson] [--pretty] [--summary] [--field-only]";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Invalid(e)) => {
            eprintln!("{}", e.to_json());
            ExitCode::from(2)
        }
        Err(Failure::Usage(message)) => {
            eprintln!("{}", json_line("usage", &format!("{message}; {USAGE}")));
            ExitCode::from(2)
        }
        Err(Failure::Io(message)) => {
            eprintln!("{}", json_line("io_error", &message));
            ExitCode::from(1)
        }
    }
}

enum Failure {
    Invalid(PlanError),
    Usage(String),
    Io(String),
}

/// What the command line asks for.
struct Command {
    field: String,
    options: Map<String, Value>,
    out: Option<String>,
    pretty: bool,
    summary_only: bool,
    path: Option<PathQuery>,
    /// The parcel of a file of several to plan.
    parcel: Option<usize>,
    /// Print the field as read, not its plan.
    field_only: bool,
    /// The plan as ISOXML TaskData (zipped) rather than GeoJSON.
    format: Option<TaskDataVersion>,
    /// The headland passes as AB segments in the TaskData.
    curves_as_ab: bool,
    /// The plan as KML rather than GeoJSON.
    kml: bool,
}

/// A shortest-path question (`--from`, `--heading`, `--to`, `--turning`).
struct PathQuery {
    from: [f64; 2],
    heading_deg: f64,
    to: Vec<[f64; 2]>,
    turning: Turning,
}

fn run(args: &[String]) -> Result<(), Failure> {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        print_help();
        return Ok(());
    }
    let command = parse_args(args)?;
    let options: PlanOptions =
        serde_json::from_value(Value::Object(command.options)).map_err(|e| {
            Failure::Invalid(PlanError::new(
                furrow::ErrorCode::InvalidOption,
                format!("invalid option: {}", kebab_message(&e.to_string())),
            ))
        })?;
    let text = read_field(&command.field, command.parcel, command.field_only)?;
    if command.field_only {
        let mut out = text;
        out.push('\n');
        return write_out(&command.out, &out);
    }
    let plan = plan_geojson(&text, &options).map_err(Failure::Invalid)?;
    if let Some(q) = &command.path {
        let tracks = PlanTracks::from_plan(&plan);
        let path = tracks
            .shortest_path(q.from, q.heading_deg, &q.to, q.turning)
            .map_err(Failure::Invalid)?;
        let mut out = to_json(&tracks.to_feature(&path, q.turning), command.pretty);
        out.push('\n');
        return write_out(&command.out, &out);
    }
    if command.kml {
        let mut out = plan_kml(&text, &plan.to_geojson_string()).map_err(Failure::Invalid)?;
        out.push('\n');
        return write_out(&command.out, &out);
    }
    if let Some(format) = command.format {
        let settings = TaskDataSettings {
            width_m: options.width,
            version: format,
            curves_as_ab: command.curves_as_ab,
            name: None,
        };
        let zip =
            taskdata_zip(&text, &plan.to_geojson_string(), &settings).map_err(Failure::Invalid)?;
        return write_bytes(&command.out, &zip);
    }
    let geojson = plan.to_geojson();
    let mut out = if command.summary_only {
        to_json(&geojson.summary, command.pretty)
    } else {
        to_json(&geojson, command.pretty)
    };
    out.push('\n');
    write_out(&command.out, &out)
}

/// Writes `text` to the file `out` names, or to standard output.
fn write_out(out: &Option<String>, text: &str) -> Result<(), Failure> {
    write_bytes(out, text.as_bytes())
}

fn write_bytes(out: &Option<String>, bytes: &[u8]) -> Result<(), Failure> {
    match out {
        Some(path) => std::fs::write(path, bytes)
            .map_err(|e| Failure::Io(format!("cannot write {path}: {e}")))?,
        None => std::io::stdout()
            .lock()
            .write_all(bytes)
            .map_err(|e| Failure::Io(format!("cannot write the plan: {e}")))?,
    }
    Ok(())
}

/// `LON,LAT` (or `x,y` in metres) as a position.
fn position(flag: &str, text: Option<String>) -> Result<[f64; 2], Failure> {
    let text = text.ok_or_else(|| Failure::Usage(format!("--{flag} needs LON,LAT")))?;
    match numbers(&text).as_deref() {
        Some(&[x, y]) => Ok([x, y]),
        _ => Err(Failure::Usage(format!("--{flag} {text}: not LON,LAT"))),
    }
}

/// Whether the flag is a yes-or-no one, `true` without a value.
fn is_switch(flag: &str) -> bool {
    let key = camel_case(flag);
    matches!(flag, "pretty" | "summary" | "field-only" | "curves-as-ab")
        || OPTION_DOCS
            .iter()
            .any(|(k, unit, _)| *k == key && *unit == "true|false")
}

/// Comma-separated finite numbers (`24.05,60.25`), or `None` when the text is anything else.
fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split(',')
        .map(|p| p.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect()
}

/// The planner options that are positions, with how many positions each holds: on the command
/// line they are written `x,y` (`x,y,x,y` for two), as well as in JSON.
const POSITION_OPTIONS: &[(&str, usize)] = &[("entrance", 1), ("exit", 1), ("referenceLine", 2)];

/// The value of the planner option `key` (`--flag`) as JSON.
fn option_value(flag: &str, key: &str, text: Option<String>) -> Result<Value, Failure> {
    let unit = OPTION_DOCS
        .iter()
        .find(|(k, _, _)| *k == key)
        .map(|(_, unit, _)| *unit);
    let Some(text) = text else {
        // A bare flag is `true` for a yes-or-no option (and for an unknown one, which the
        // options then refuse by its name); any other option needs its value.
        return match unit {
            Some(unit) if unit != "true|false" => Err(invalid_option(format!(
                "--{flag} needs a value: --{flag} <{unit}>"
            ))),
            _ => Ok(Value::Bool(true)),
        };
    };
    let positions = POSITION_OPTIONS
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, n)| *n);
    match positions {
        Some(n) if !text.trim_start().starts_with('[') && text.trim() != "null" => {
            let xy = numbers(&text)
                .filter(|xy| xy.len() == 2 * n)
                .ok_or_else(|| {
                    let form = if n == 1 { "x,y" } else { "x,y,x,y" };
                    invalid_option(format!(
                        "--{flag} {text}: expected {form} (numbers separated by commas, in the input's coordinates, such as {})",
                        if n == 1 { "24.05,60.25" } else { "24.05,60.25,24.056,60.252" }
                    ))
                })?;
            Ok(match xy[..] {
                [x, y] => serde_json::json!([x, y]),
                _ => Value::Array(xy.chunks(2).map(|p| serde_json::json!(p)).collect()),
            })
        }
        _ => Ok(flag_value(&text)),
    }
}

fn invalid_option(message: String) -> Failure {
    Failure::Invalid(PlanError::new(ErrorCode::InvalidOption, message))
}

fn parse_args(args: &[String]) -> Result<Command, Failure> {
    let mut field = None;
    let mut options = Map::new();
    let mut out = None;
    let (mut pretty, mut summary_only, mut field_only) = (false, false, false);
    let (mut parcel, mut format, mut curves_as_ab, mut kml) = (None, None, false, false);
    let (mut from, mut heading, mut to, mut turning) = (None, None, Vec::new(), None);
    let mut i = 0;
    while i < args.len() {
        let arg = &args[i];
        i += 1;
        let Some(flag) = arg.strip_prefix("--") else {
            if field.replace(arg.clone()).is_some() {
                return Err(Failure::Usage(format!("more than one field given ({arg})")));
            }
            continue;
        };
        // `--flag=value` or `--flag value`.
        let (name, inline) = match flag.split_once('=') {
            Some((n, v)) => (n, Some(v.to_string())),
            None => (flag, None),
        };
        // A switch (`--summary`, `--reverse`) takes only `true` or `false` after it, so that
        // `--reverse FIELD` leaves the field alone.
        let takes = |next: &String| {
            !next.starts_with("--") && (!is_switch(name) || next == "true" || next == "false")
        };
        let value = match inline {
            Some(v) => Some(v),
            None if args.get(i).is_some_and(takes) => {
                i += 1;
                Some(args[i - 1].clone())
            }
            None => None,
        };
        match name {
            "out" => out = Some(value.ok_or_else(|| Failure::Usage("--out needs a path".into()))?),
            "pretty" => pretty = true,
            "summary" => summary_only = true,
            "field-only" => field_only = true,
            "curves-as-ab" => curves_as_ab = true,
            "format" => {
                kml = value.as_deref() == Some("kml");
                format = match value.as_deref() {
                    Some("geojson") | Some("kml") => None,
                    Some("isoxml") => Some(TaskDataVersion::V4),
                    Some("isoxml-v3") => Some(TaskDataVersion::V3),
                    v => {
                        return Err(Failure::Usage(format!(
                            "--format {}: expected geojson, kml, isoxml or isoxml-v3",
                            v.unwrap_or_default()
                        )))
                    }
                };
            }
            "parcel" => {
                let v = value.unwrap_or_default();
                parcel = Some(v.trim().parse::<usize>().map_err(|_| {
                    Failure::Usage(format!(
                        "--parcel {v}: not the index of a parcel (0 for the first)"
                    ))
                })?);
            }
            "from" => from = Some(position("from", value)?),
            "to" => to.push(position("to", value)?),
            "heading" => {
                let v = value.ok_or_else(|| Failure::Usage("--heading needs degrees".into()))?;
                heading = Some(
                    v.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|h| h.is_finite())
                        .ok_or_else(|| {
                            Failure::Usage(format!("--heading {v}: not a number of degrees"))
                        })?,
                );
            }
            "turning" => {
                let v = value.unwrap_or_default();
                turning = Some(Turning::parse(&v).ok_or_else(|| {
                    Failure::Invalid(PlanError::new(
                        ErrorCode::InvalidOption,
                        format!("--turning {v}: expected tracks, heading or on-the-spot"),
                    ))
                })?);
            }
            _ => {
                let key = camel_case(name);
                let v = option_value(name, &key, value)?;
                options.insert(key, v);
            }
        }
    }
    let field = field.ok_or_else(|| Failure::Usage("no field given".into()))?;
    let path = match (from, to.is_empty()) {
        (None, true) if heading.is_none() && turning.is_none() => None,
        (Some(from), false) => {
            let turning = turning.unwrap_or_default();
            let heading_deg = match (heading, turning) {
                (Some(h), _) => h,
                (None, Turning::OnTheSpot) => 0.0,
                (None, _) => {
                    return Err(Failure::Usage(
                        "--heading is needed unless --turning on-the-spot".into(),
                    ))
                }
            };
            Some(PathQuery {
                from,
                heading_deg,
                to,
                turning,
            })
        }
        _ => {
            return Err(Failure::Usage(
                "a shortest path needs --from LON,LAT and --to LON,LAT (and --heading DEG)".into(),
            ))
        }
    };
    Ok(Command {
        field,
        options,
        out,
        pretty,
        summary_only,
        path,
        parcel,
        field_only,
        format,
        curves_as_ab,
        kml,
    })
}

/// A flag's text as a JSON value: a number, `true`/`false`/`null`, JSON for `[...]` and `{...}`,
/// otherwise a string.
fn flag_value(text: &str) -> Value {
    if let Ok(x) = text.parse::<f64>() {
        if let Some(n) = serde_json::Number::from_f64(x) {
            // Whole numbers stay integers, so that count options (u32) accept them.
            if x.fract() == 0.0 && x.abs() < 9e15 {
                return Value::from(x as i64);
            }
            return Value::Number(n);
        }
    }
    match text {
        "true" => return Value::Bool(true),
        "false" => return Value::Bool(false),
        "null" => return Value::Null,
        _ => {}
    }
    if text.starts_with('[') || text.starts_with('{') {
        if let Ok(v) = serde_json::from_str(text) {
            return v;
        }
    }
    Value::String(text.to_string())
}

/// `headland-passes` to `headlandPasses`.
fn camel_case(kebab: &str) -> String {
    let mut out = String::with_capacity(kebab.len());
    let mut upper = false;
    for c in kebab.chars() {
        if c == '-' {
            upper = true;
        } else if upper {
            out.extend(c.to_uppercase());
            upper = false;
        } else {
            out.push(c);
        }
    }
    out
}

/// `headlandPasses` to `headland-passes`.
fn kebab_case(camel: &str) -> String {
    let mut out = String::with_capacity(camel.len() + 4);
    for c in camel.chars() {
        if c.is_uppercase() {
            out.push('-');
            out.extend(c.to_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// serde names options in camelCase; on the command line they are flags. Only option names
/// become flags: the unknown one and the known ones serde lists, not quoted values.
fn kebab_message(message: &str) -> String {
    let mut out = String::new();
    for (k, part) in message.split('`').enumerate() {
        if k > 0 {
            out.push('`');
        }
        let quoted = k % 2 == 1;
        let name =
            out.ends_with("unknown field `") || OPTION_DOCS.iter().any(|(key, _, _)| *key == part);
        if quoted && name {
            out.push_str("--");
            out.push_str(&kebab_case(part));
        } else {
            out.push_str(part);
        }
    }
    out
}

/// Reads the field's text from the file `path` names, or from standard input (`-`): at most
/// [`MAX_INPUT_BYTES`] and one byte more, so that an input too large is refused without reading
/// it all. Text that is too large or not UTF-8 is the input's fault (exit 2), not the file's.
/// The field file `path` names as GeoJSON text: GeoJSON as it is, a zipped Shapefile, KML or
/// KMZ read into GeoJSON; with `parcel`, only that parcel of the file (a feature of a FeatureCollection).
/// A Shapefile of several parcels is refused without `parcel` unless `all` are asked for.
fn read_field(path: &str, parcel: Option<usize>, all: bool) -> Result<String, Failure> {
    let bytes = read_input(path)?;
    let mut geojson = if is_field_file(&bytes) {
        let mut file = read_field_file(&bytes, path).map_err(Failure::Invalid)?;
        let count = file.parcels.len();
        if count > 1 && parcel.is_none() && !all {
            return Err(Failure::Invalid(PlanError::new(
                ErrorCode::AmbiguousBoundary,
                format!("{path} holds {count} parcels: plan one with --parcel INDEX (0 to {}), or see them with --field-only", count - 1),
            )));
        }
        // The parcel picked as a file of its own: a TaskData partfield with its AB line.
        if let Some(index) = parcel.filter(|&i| i < count) {
            file.parcels = vec![file.parcels.swap_remove(index)];
            return Ok(file.to_geojson_string());
        }
        file.to_geojson()
    } else {
        let text = String::from_utf8(bytes)
            .map_err(|e| Failure::Invalid(not_utf8(e.as_bytes(), e.utf8_error())))?;
        match parcel {
            None => return Ok(text),
            Some(_) => serde_json::from_str(&text).map_err(|e| {
                Failure::Invalid(PlanError::new(
                    ErrorCode::InvalidJson,
                    format!("the input is not JSON: {e}"),
                ))
            })?,
        }
    };
    if let Some(index) = parcel {
        let features = geojson.get_mut("features").and_then(Value::as_array_mut);
        let count = features.as_ref().map_or(0, |f| f.len());
        let picked = features
            .filter(|f| index < f.len())
            .map(|f| f.swap_remove(index))
            .ok_or_else(|| {
                Failure::Usage(format!(
                    "--parcel {index}: the file holds {count} parcel{}",
                    if count == 1 { "" } else { "s" }
                ))
            })?;
        geojson["features"] = Value::Array(vec![picked]);
    }
    Ok(geojson.to_string())
}

/// The bytes of the file `path` names (`-`: standard input): GeoJSON text up to its limit, a
/// zip archive (a Shapefile) up to the field files' own.
fn read_input(path: &str) -> Result<Vec<u8>, Failure> {
    let name = if path == "-" { "standard input" } else { path };
    let io = |e: std::io::Error| Failure::Io(format!("cannot read {name}: {e}"));
    let mut source: Box<dyn Read> = if path == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        let file = std::fs::File::open(path).map_err(io)?;
        // A regular file says its size; a pipe or device says 0 and is cut off by `take`.
        if let Ok(meta) = file.metadata() {
            if meta.len() > MAX_FILE_BYTES as u64 {
                return Err(too_large(&format!("{} MB", meta.len() / (1024 * 1024))));
            }
        }
        Box::new(file)
    };
    let mut bytes = Vec::new();
    source
        .by_ref()
        .take(MAX_INPUT_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() > MAX_INPUT_BYTES {
        if !is_field_file(&bytes) {
            return Err(too_large(&format!(
                "more than {} MB",
                MAX_INPUT_BYTES / (1024 * 1024)
            )));
        }
        source
            .take((MAX_FILE_BYTES - MAX_INPUT_BYTES) as u64 + 1)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        if bytes.len() > MAX_FILE_BYTES {
            return Err(too_large(&format!(
                "more than {} MB",
                MAX_FILE_BYTES / (1024 * 1024)
            )));
        }
    }
    Ok(bytes)
}

fn too_large(size: &str) -> Failure {
    Failure::Invalid(PlanError::new(
        ErrorCode::InputTooLarge,
        format!(
            "the input is {size}; the planner accepts up to {} MB of GeoJSON and {} MB of a zipped Shapefile",
            MAX_INPUT_BYTES / (1024 * 1024),
            MAX_FILE_BYTES / (1024 * 1024)
        ),
    ))
}

/// The error for input that is not UTF-8, as JSON text must be: where the first bad byte is.
fn not_utf8(bytes: &[u8], e: std::str::Utf8Error) -> PlanError {
    let good = &bytes[..e.valid_up_to()];
    let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
    let column = good.len() - good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
    PlanError::new(
        ErrorCode::InvalidJson,
        format!(
            "the input is not UTF-8 text, as JSON must be: byte {} (line {line}, column {column}) is not UTF-8; save the file as UTF-8",
            e.valid_up_to()
        ),
    )
    .at_text(line, column)
}

fn json_line(code: &str, message: &str) -> String {
    serde_json::json!({ "code": code, "message": message }).to_string()
}

fn print_help() {
    println!(
        "furrow {}: plan coverage paths for a field\n",
        env!("CARGO_PKG_VERSION")
    );
    println!("{USAGE}\n");
    println!("FIELD is GeoJSON (a FeatureCollection with roles, a Feature or a Polygon) a zipped Shapefile (.zip with .shp, .shx, .dbf, .prj), KML, KMZ or ISOXML TaskData (TASKDATA.XML or its zip); - reads standard input.\n");
    println!("  --{:<22} {:<13} the parcel to plan of a file of several (a register's export), 0 for the first", "parcel", "<index>");
    println!(
        "  --{:<22} {:<13} print the field as read (GeoJSON in WGS84) instead of planning it\n",
        "field-only", ""
    );
    println!("Planner options:");
    for (key, unit, doc) in OPTION_DOCS {
        println!(
            "  --{:<22} {:<13} {doc}",
            kebab_case(key),
            format!("<{unit}>")
        );
    }
    println!("\nOutput:");
    println!(
        "  --{:<22} {:<13} write the plan to a file instead of standard output",
        "out", "<path>"
    );
    println!("  --{:<22} {:<13} indent the JSON", "pretty", "");
    println!(
        "  --{:<22} {:<13} the plan as GeoJSON (default), KML (Google Earth), or ISOXML TaskData for ISOBUS terminals (zipped TASKDATA/TASKDATA.XML; isoxml-v3 for older ones)",
        "format", "<geojson|kml|isoxml|isoxml-v3>"
    );
    println!(
        "  --{:<22} {:<13} in ISOXML, the headland passes as AB segments, for terminals that take no curves",
        "curves-as-ab", ""
    );
    println!(
        "  --{:<22} {:<13} print only the plan's summary",
        "summary", ""
    );
    println!(
        "\nShortest path along the plan's tracks (prints a GeoJSON Feature instead of the plan):"
    );
    println!(
        "  --{:<22} {:<13} where the machine is",
        "from", "<lon,lat>"
    );
    println!(
        "  --{:<22} {:<13} where it faces, compass degrees",
        "heading", "<deg>"
    );
    println!(
        "  --{:<22} {:<13} an exit on the boundary lane (repeat for several)",
        "to", "<lon,lat>"
    );
    println!("  --{:<22} {:<13} heading (no turning on the spot, default), tracks (only as driven) or on-the-spot", "turning", "<name>");
    println!("\nExit status: 0 planned; 2 invalid input (also over 32 MB or not UTF-8) or option (one JSON line on stderr); 1 file error.");
}

fn to_json<T: serde::Serialize>(value: &T, pretty: bool) -> String {
    let text = if pretty {
        serde_json::to_string_pretty(value)
    } else {
        serde_json::to_string(value)
    };
    // ok: plan output holds only strings, integers and finite floats.
    text.unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_are_x_comma_y() {
        let value = |key: &str, text: &str| option_value(key, key, Some(text.into())).ok();
        let point = serde_json::json!([24.05, 60.25]);
        assert_eq!(value("entrance", "24.05,60.25"), Some(point.clone()));
        assert_eq!(value("exit", " 24.05, 60.25 "), Some(point.clone()));
        assert_eq!(value("entrance", "[24.05,60.25]"), Some(point));
        assert_eq!(value("entrance", "null"), Some(Value::Null));
        assert_eq!(
            value("referenceLine", "1,2,3,4"),
            Some(serde_json::json!([[1.0, 2.0], [3.0, 4.0]]))
        );
        for (key, text) in [
            ("entrance", "24.05"),
            ("entrance", "24.05,60.25,1"),
            ("exit", "24.05,north"),
            ("entrance", "NaN,1"),
            ("referenceLine", "1,2"),
        ] {
            assert!(value(key, text).is_none(), "{key} {text}");
        }
    }

    #[test]
    fn only_switches_go_without_a_value() {
        assert_eq!(
            option_value("reverse", "reverse", None).ok(),
            Some(Value::Bool(true))
        );
        let Err(Failure::Invalid(e)) = option_value("width", "width", None) else {
            panic!("--width without a value is refused");
        };
        assert_eq!(e.code, ErrorCode::InvalidOption);
        assert_eq!(e.message, "--width needs a value: --width <metres>");
        assert!(is_switch("reverse") && is_switch("summary") && !is_switch("width"));
    }

    #[test]
    fn messages_name_flags_not_values() {
        assert_eq!(
            kebab_message("unknown field `widht`, expected one of `width`, `headlandPasses`"),
            "unknown field `--widht`, expected one of `--width`, `--headland-passes`"
        );
        assert_eq!(
            kebab_message("invalid type: boolean `true`, expected f64"),
            "invalid type: boolean `true`, expected f64"
        );
        assert_eq!(
            kebab_message("invalid value: integer `-1`, expected u32"),
            "invalid value: integer `-1`, expected u32"
        );
    }

    #[test]
    fn flag_names_and_values() {
        assert_eq!(camel_case("headland-passes"), "headlandPasses");
        assert_eq!(kebab_case("minSwathLength"), "min-swath-length");
        assert_eq!(flag_value("6"), Value::from(6));
        assert_eq!(flag_value("4.95"), Value::from(4.95));
        assert_eq!(flag_value("metric"), Value::from("metric"));
        assert_eq!(flag_value("[[10,20]]"), serde_json::json!([[10, 20]]));
    }
}
