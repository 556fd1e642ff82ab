//! The memory it takes to refuse an input too large: 32 MB of tiny arrays (positions, empty
//! lists, features, forbidden ranges) must be refused as `input_too_large` without building them
//! all. An allocator that counts bytes measures the peak while the input is read; this file is
//! a test binary of its own so that nothing else allocates meanwhile.

use furrow::{plan_geojson, ErrorCode, PlanOptions};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the bytes allocated now and at the most.
struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: passed on to the system allocator with the caller's layout.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = NOW.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        // SAFETY: `p` came from `alloc` above with this layout.
        unsafe { System.dealloc(p, layout) };
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// 31 MB of `unit` repeated between `head` and `tail`.
fn input(head: &str, unit: &str, tail: &str) -> String {
    let n = (31 * 1024 * 1024 - head.len() - tail.len()) / unit.len();
    let mut text = String::with_capacity(head.len() + n * unit.len() + tail.len());
    text.push_str(head);
    for _ in 0..n {
        text.push_str(unit);
    }
    text.pop(); // the last comma
    text.push_str(tail);
    text
}

#[test]
fn tiny_arrays_are_refused_in_little_memory() {
    let polygon = |unit: &str| input(r#"{"type":"Polygon","coordinates":[["#, unit, "]]}");
    let cases = [
        ("positions", polygon("[0,0],")),
        ("one-number lists", polygon("[0],")),
        ("empty lists", polygon("[],")),
        (
            "empty rings",
            input(r#"{"type":"Polygon","coordinates":["#, "[],", "]}"),
        ),
        (
            "features",
            input(
                r#"{"type":"FeatureCollection","features":["#,
                r#"{"type":"Feature","geometry":null},"#,
                "]}",
            ),
        ),
        (
            "forbidden ranges",
            input(
                r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"role":"prohibited","forbidden_bearings_deg":["#,
                "[0,1],",
                r#"]},"geometry":null}]}"#,
            ),
        ),
    ];
    for (what, text) in cases {
        let before = NOW.load(Ordering::Relaxed);
        PEAK.store(before, Ordering::Relaxed);
        let e = plan_geojson(&text, &PlanOptions::default()).expect_err("refused");
        let peak_mb = (PEAK.load(Ordering::Relaxed) - before) as f64 / 1e6;
        assert_eq!(e.code, ErrorCode::InputTooLarge, "{what}: {}", e.message);
        // Beyond the text itself (31 MB, allocated before): a few megabytes for what is kept
        // up to the limits, where building everything took up to a gigabyte.
        assert!(peak_mb < 24.0, "{what}: {peak_mb:.1} MB allocated");
        eprintln!("{what}: refused with {peak_mb:.1} MB allocated");
    }
}
