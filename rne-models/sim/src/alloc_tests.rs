//! Checks that the step loops do not allocate, with a counting global allocator installed in
//! the crate's test binary (tests only; it forwards to the system allocator).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use super::test_models::{FreeBody, PlanarElbow};
use super::*;

thread_local! {
    /// Allocations made by the current thread (tests run on separate threads).
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

/// The system allocator, counting allocations per thread.
struct Counting;

// SAFETY: every call is forwarded unchanged to the system allocator; the counter is a
// const-initialised thread-local without destructor, so touching it never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// Allocations made by the current thread while running `f`.
fn allocations_in(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// Property: no integrator allocates while stepping. Each runs 5 s of the released double
/// pendulum (thousands of steps) with a sink that stores nothing, under a saturated PD input.
#[test]
fn integrators_do_not_allocate_per_step() {
    let arm = PlanarElbow::thesis();
    let x0 = State::at_rest([0.0, 0.0]);
    let pd = Pd::new([22.0, 45.0], [15.0, 8.0], [1.0, 1.0]).saturated([39.4; 2]);
    let times = [0.0, 1.0, 2.5, 5.0];
    let methods = [
        Method::Rk4(Rk4::new(1e-3)),
        Method::Dopri5(Dopri5::new(1e-10, 1e-12)),
        Method::Dopri5(Dopri5 {
            step_to_outputs: true,
            ..Dopri5::new(1e-10, 1e-12)
        }),
        Method::GaussLegendre(GaussLegendre::new(1e-3)),
    ];
    for method in methods {
        let mut stats = Stats::default();
        let n = allocations_in(|| {
            stats = method.integrate(&arm, &pd, &x0, &times, |_, _| {}).unwrap();
        });
        assert!(stats.steps > 1000, "{method:?}: {stats:?}");
        assert_eq!(n, 0, "{method:?} allocated {n} times");
    }
    // `simulate` allocates the record once, whatever the number of steps.
    let n = allocations_in(|| {
        let r = simulate(&arm, &pd, &Dopri5::new(1e-10, 1e-12), &x0, &times).unwrap();
        assert_eq!(r.len(), 4);
    });
    assert!((1..=8).contains(&n), "{n} allocations");
}

/// Property: the variational integrator does not allocate while stepping either, on a floating
/// base (a free body falling and tumbling for 5 s, thousands of steps).
#[test]
fn the_variational_integrator_does_not_allocate_per_step() {
    let body = FreeBody {
        m: 2.0,
        inertia: [0.1, 0.2, 0.3],
        gravity: [0.0, 0.0, -9.81],
    };
    let x0 = ManifoldState::new(
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        [0.1, 0.0, 0.0, 0.01, 3.0, 0.02],
    );
    let push = |t: f64, _: &[f64; 7], _: &[f64; 6]| [0.0, 0.0, 0.0, 0.1 * t.sin(), 0.0, 0.0];
    let mut stats = Stats::default();
    let n = allocations_in(|| {
        stats = LieVariational::new(1e-3)
            .integrate(&body, &push, &x0, &[0.0, 1.0, 2.5, 5.0], |_, _| {})
            .unwrap();
    });
    assert!(stats.steps > 1000, "{stats:?}");
    assert_eq!(n, 0, "allocated {n} times");
}
