//! The mesh generators' limits (issue #32, item 11; fuzz finds): a mesh has at most 65536
//! vertices (`u16` indices), and `torus`, `torus_knot` and `icosphere` panic on parameters
//! beyond that before they build anything — `torus(1.0, 0.5, 3000, 3000)` built 9·10⁶ vertices
//! (2.45 s) before its documented panic, and `rings = 2⁶² + 1, sides = 4`, whose product wraps
//! to 4 in release builds, aborted on a 3 GB allocation. Bytes allocated are counted (not time):
//! this test binary's allocator counts them per thread.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::panic::{self, catch_unwind, UnwindSafe};
use std::sync::Once;

use embedded_raster::three_d::meshes::{icosphere, torus, torus_knot};

/// The system allocator, counting the bytes each thread asks for.
struct Counting;

thread_local! {
    static ALLOCATED: Cell<usize> = const { Cell::new(0) };
}

fn count(bytes: usize) {
    // `try_with`: not during the thread's teardown.
    let _ = ALLOCATED.try_with(|a| a.set(a.get().saturating_add(bytes)));
}

fn allocated() -> usize {
    ALLOCATED.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// More than the panic's message and machinery take, far less than a mesh beyond the limit
/// (65,537 vertices of `f64` positions alone: 1.5 MB).
const SMALL: usize = 64 << 10;

thread_local! {
    /// Whether the thread is in [`panic_of`], whose panics the hook keeps quiet.
    static EXPECTED: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f`, which must panic: its message, and the bytes allocated until it did. The panic is
/// not reported (the default hook's report allocates: a backtrace with `RUST_BACKTRACE` set).
fn panic_of(f: impl FnOnce() + UnwindSafe) -> (String, usize) {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let report = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !EXPECTED.with(Cell::get) {
                report(info);
            }
        }));
    });
    EXPECTED.with(|e| e.set(true));
    let before = allocated();
    let result = catch_unwind(f);
    let bytes = allocated() - before;
    EXPECTED.with(|e| e.set(false));
    let payload = result.expect_err("no panic");
    let message = match payload.downcast::<String>() {
        Ok(s) => *s,
        Err(payload) => payload
            .downcast::<&str>()
            .map(|s| s.to_string())
            .unwrap_or_default(),
    };
    (message, bytes)
}

/// What is wrong with `f`'s panic, if anything: it must allocate next to nothing and say
/// every one of `words`.
fn wrong_panic(what: &str, f: impl FnOnce() + UnwindSafe, words: &[&str]) -> Option<String> {
    let (message, bytes) = panic_of(f);
    if bytes >= SMALL {
        return Some(format!(
            "{what}: {bytes} bytes allocated before the panic ({message:?})"
        ));
    }
    let lacking: Vec<&&str> = words.iter().filter(|w| !message.contains(**w)).collect();
    (!lacking.is_empty()).then(|| format!("{what}: {message:?} lacks {lacking:?}"))
}

/// Asserts that nothing is `wrong`.
fn assert_none_wrong(wrong: Vec<Option<String>>) {
    let wrong: Vec<String> = wrong.into_iter().flatten().collect();
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn torus_beyond_the_limit_panics_before_building() {
    let huge = (1usize << 62) + 1;
    let mut wrong = Vec::new();
    for (rings, sides, product) in [
        (3000, 3000, "= 9000000"),
        (65537, 3, "= 196611"),
        (257, 256, "= 65792"),
        (huge, 4, "more than usize::MAX"),
        (1 << 32, 1 << 32, "more than usize::MAX"),
        (usize::MAX, usize::MAX, "more than usize::MAX"),
        (2, 100, "= 200"),
        (100, 0, "= 0"),
    ] {
        let given = format!("{rings} × {sides}");
        let words = ["65536", &given, product];
        wrong.push(wrong_panic(
            &format!("torus {given}"),
            move || drop(torus(1.0, 0.5, rings, sides)),
            &words,
        ));
        wrong.push(wrong_panic(
            &format!("torus_knot {given}"),
            move || drop(torus_knot((2, 3), 1.0, 0.3, rings, sides)),
            &words,
        ));
    }
    assert_none_wrong(wrong);
}

#[test]
fn icosphere_beyond_the_limit_panics_before_building() {
    let wrong = [7, 8, 40, u32::MAX].map(|subdivisions| {
        wrong_panic(
            &format!("icosphere {subdivisions}"),
            move || drop(icosphere(1.0, subdivisions)),
            &["65536", "6 subdivisions", &format!("not {subdivisions}")],
        )
    });
    assert_none_wrong(wrong.into());
}

/// The largest meshes within the limit are built: 65536 vertices exactly.
#[test]
fn the_limit_itself_is_built() {
    assert_eq!(torus(1.0, 0.5, 16384, 4).vertices.len(), 65536);
    assert_eq!(torus(1.0, 0.5, 4, 16384).vertices.len(), 65536);
    assert_eq!(torus_knot((2, 3), 1.0, 0.3, 256, 256).vertices.len(), 65536);
    assert_eq!(torus(1.0, 0.5, 3, 3).vertices.len(), 9);
    // 10 · 4⁶ + 2 vertices.
    assert_eq!(icosphere(1.0, 6).vertices.len(), 40962);
}
