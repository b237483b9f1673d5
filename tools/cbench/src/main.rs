//! Time per call of the Rust kernels that `bench.c` times in C (`run.sh` runs both): the same
//! robots and kernels, the same 1024 states from the same generator, each kernel called on
//! 128 consecutive states per run, runs repeated for a second; the figure is the fastest
//! run's time per call, in nanoseconds. Each
//! kernel is called through a function that is never inlined, as the C kernels are called
//! from another translation unit.
//!
//!     cargo run --release -- ur5     # or panda

use std::hint::black_box;
use std::time::Instant;

rne_codegen::derive_dynamics! {
    mod ur5 {
        robot: "../../rne-models/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics, inverse_dynamics_derivatives,
                  forward_dynamics_derivatives],
    }
}

rne_codegen::derive_dynamics! {
    mod panda {
        robot: "../../rne-models/robots/panda.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics, inverse_dynamics_derivatives,
                  forward_dynamics_derivatives],
    }
}

const STATES: usize = 1024;

/// bench.c's generator: xorshift64*, uniform in [-1, 1).
struct Random(u64);

impl Random {
    fn uniform(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        (x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / 4_503_599_627_370_496.0 - 1.0
    }
}

/// Calls per run.
const RUN: usize = 128;

/// Prints the best time per call of `call` over runs of [`RUN`] calls on consecutive states,
/// run for at least a second: on a shared machine, the shortest run is the one no other
/// process interrupted.
fn time(label: &str, mut call: impl FnMut(usize)) {
    let (mut best, mut total) = (f64::INFINITY, 0.0);
    let mut run = 0;
    while total < 1.0 || run < 50 {
        let first = (run * RUN) % STATES;
        let start = Instant::now();
        for s in first..first + RUN {
            call(s);
        }
        let elapsed = start.elapsed().as_secs_f64();
        total += elapsed;
        best = best.min(elapsed);
        run += 1;
    }
    println!("{label:<32} {:9.1} ns", best / RUN as f64 * 1e9);
}

/// Times robot module `$m`'s kernels, with `$n` joints.
macro_rules! bench {
    ($m:ident, $n:literal) => {{
        #[inline(never)]
        fn id(q: &[f64; $n], qd: &[f64; $n], qdd: &[f64; $n], out: &mut [f64; $n]) {
            *out = $m::inverse_dynamics(q, qd, qdd);
        }
        #[inline(never)]
        fn m(q: &[f64; $n], out: &mut [[f64; $n]; $n]) {
            *out = $m::mass_matrix(q);
        }
        #[inline(never)]
        fn fd(q: &[f64; $n], qd: &[f64; $n], tau: &[f64; $n], out: &mut [f64; $n]) {
            *out = $m::forward_dynamics(q, qd, tau);
        }
        type Square = [[f64; $n]; $n];
        #[inline(never)]
        fn did(q: &[f64; $n], qd: &[f64; $n], qdd: &[f64; $n], out: &mut (Square, Square)) {
            *out = $m::inverse_dynamics_derivatives(q, qd, qdd);
        }
        #[inline(never)]
        fn dfd(q: &[f64; $n], qd: &[f64; $n], tau: &[f64; $n], out: &mut (Square, Square, Square)) {
            *out = $m::forward_dynamics_derivatives(q, qd, tau);
        }
        let mut random = Random(0x9E37_79B9_7F4A_7C15);
        let mut states = Vec::with_capacity(STATES);
        for _ in 0..STATES {
            let q: [f64; $n] = std::array::from_fn(|_| 3.0 * random.uniform());
            let qd: [f64; $n] = std::array::from_fn(|_| 2.0 * random.uniform());
            let qdd: [f64; $n] = std::array::from_fn(|_| 5.0 * random.uniform());
            states.push((q, qd, qdd));
        }
        let states = black_box(states);
        let mut vector = [0.0; $n];
        let mut matrix = [[0.0; $n]; $n];
        let mut pair = ([[0.0; $n]; $n], [[0.0; $n]; $n]);
        let mut triple = ([[0.0; $n]; $n], [[0.0; $n]; $n], [[0.0; $n]; $n]);
        time("inverse_dynamics", |s| {
            let (q, qd, qdd) = &states[s];
            id(q, qd, qdd, &mut vector);
            black_box(&vector);
        });
        time("mass_matrix", |s| {
            m(&states[s].0, &mut matrix);
            black_box(&matrix);
        });
        time("forward_dynamics", |s| {
            let (q, qd, tau) = &states[s];
            fd(q, qd, tau, &mut vector);
            black_box(&vector);
        });
        time("inverse_dynamics_derivatives", |s| {
            let (q, qd, qdd) = &states[s];
            did(q, qd, qdd, &mut pair);
            black_box(&pair);
        });
        time("forward_dynamics_derivatives", |s| {
            let (q, qd, tau) = &states[s];
            dfd(q, qd, tau, &mut triple);
            black_box(&triple);
        });
    }};
}

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("ur5") => bench!(ur5, 6),
        Some("panda") => bench!(panda, 9),
        _ => {
            eprintln!("usage: rne-cbench ur5|panda");
            std::process::exit(2);
        }
    }
}
