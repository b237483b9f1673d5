//! The C emitter (`rne emit --lang c`, [`generate_c`]): the C of every built-in robot's every
//! kernel, compiled by the system's C compiler (`$CC`, else `cc`) with `-std=c99 -Wall
//! -Wextra -pedantic -Werror` and as C++ (`$CXX`, else `c++`), computes bit for bit what the
//! Rust kernels compute: each kernel's program evaluated in `f64` ([`Program::eval`], bit
//! for bit the emitted Rust), the compiled kernels of rne-models (every built-in robot's
//! dynamics, the URDF robots' control kernels, the TOML robots' runtime parameters) and of
//! modules generated here (UR5 with every kernel, a floating base, base parameters); and
//! within 1e-15 of the Rust derivatives built in lanes (which C builds in scalars) at random
//! states. The ported
//! sine and cosine equal the runtime's on every kind of argument, and the output is the same
//! bytes every time. The C is compiled with `-mfma` exactly when this test is built with the
//! `fma` target feature, as the header documents. Skipped, with a message, where there is no
//! C compiler.

mod common;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rne_codegen::{Dynamics, Kernel};
use rne_codegen_core::{
    emit_c, generate_programs, CModule, GeneratedPrograms, GenerationOptions, ParameterMode,
    Program, Scene, Shape,
};
use rne_models::{RobotSource, Visitor, BUILTIN_ROBOTS};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{RobotModel, Symbol};

rne_codegen::derive_dynamics! {
    /// UR5 with every kernel.
    mod ur5_all {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques, bias_torques,
                  forward_dynamics, kinetic_energy, potential_energy,
                  inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse,
                  frame_placements, frame_jacobians, frame_jacobian_dot_qd, friction_torques,
                  regressor, base_regressor, base_parameters],
    }
}

rne_codegen::derive_dynamics! {
    /// A floating base: q holds the base's position and quaternion first.
    mod hopper {
        robot: "fixtures/robots/hopper-floating.toml",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics, inverse_dynamics_derivatives,
                  frame_placements],
    }
}

rne_codegen::derive_dynamics! {
    /// Friction (the sign of the velocities) and a revolute joint following another (the
    /// sine and cosine of something other than a joint angle).
    mod geared {
        robot: "fixtures/robots/geared-arm.toml",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics, friction_torques,
                  inverse_dynamics_derivatives, frame_placements],
        friction: include,
    }
}

rne_codegen::derive_dynamics! {
    /// The base parameters read at run time.
    mod elbow_base {
        robot: "fixtures/robots/planar-elbow.toml",
        outputs: [inverse_dynamics, mass_matrix, base_regressor],
        parameters: base,
    }
}

rne_codegen::derive_dynamics! {
    /// UR5's derivatives built in lanes, which C builds in scalars.
    mod ur5_lanes {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives],
        derivatives: lanes,
    }
}

/// States per kernel.
const STATES: usize = 24;

/// The C and C++ compilers, or `None` (with a message) where there is no C compiler.
struct Compilers {
    cc: String,
    cxx: Option<String>,
}

fn compilers() -> Option<Compilers> {
    let runs = |program: &str| {
        Command::new(program)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    };
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_owned());
    if !runs(&cc) {
        eprintln!("skipped: no C compiler (`{cc} --version` does not run; set CC to one)");
        return None;
    }
    let cxx = std::env::var("CXX").unwrap_or_else(|_| "c++".to_owned());
    let cxx = runs(&cxx).then_some(cxx);
    if cxx.is_none() {
        eprintln!("no C++ compiler: the C is not compiled as C++ (set CXX to one)");
    }
    Some(Compilers { cc, cxx })
}

/// The flags the C is compiled with: warnings as errors, `-mfma` exactly when the Rust build
/// fuses its multiply-adds (the header's rule for bit-for-bit results), then those of
/// `RNE_C_TEST_FLAGS`, e.g. `-O3 -march=native -std=gnu99` beside a Rust build for the
/// machine (GNU C contracts products and sums unless the source forbids it).
fn c_flags() -> Vec<String> {
    let mut flags: Vec<String> = [
        "-std=c99",
        "-O1",
        "-Wall",
        "-Wextra",
        "-pedantic",
        "-Werror",
    ]
    .map(str::to_owned)
    .to_vec();
    if cfg!(all(target_arch = "x86_64", target_feature = "fma")) {
        flags.push("-mfma".to_owned());
    }
    if let Ok(extra) = std::env::var("RNE_C_TEST_FLAGS") {
        flags.extend(extra.split_whitespace().map(str::to_owned));
    }
    flags
}

/// A directory of its own for `label` under the target directory.
fn scratch(label: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("c_kernels")
        .join(label);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    dir
}

/// Runs `command`, panicking with its output if it fails; returns its standard output.
fn run(command: &mut Command) -> Vec<u8> {
    let output = command.output().expect("the command starts");
    assert!(
        output.status.success(),
        "{command:?} failed:\n{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output.stdout
}

/// One state: the arrays a kernel may take.
#[derive(Clone, Debug)]
struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    tau: Vec<f64>,
    standard: Vec<f64>,
}

impl State {
    /// A seeded random state of `module`'s sizes; some velocities exactly ±0 (the sign of
    /// friction), state 1 at zero and state 2 with an angle beyond the sine's fast path.
    fn random(module: &GeneratedPrograms, rng: &mut ChaCha8Rng, k: usize) -> State {
        let nv = module.dims.nv;
        let mut uniform = |n: usize, bound: f64| -> Vec<f64> {
            (0..n).map(|_| rng.gen_range(-bound..=bound)).collect()
        };
        let mut q = uniform(module.nq, std::f64::consts::PI);
        if module.floating_base {
            let quaternion = &mut q[3..7];
            let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
            quaternion.iter_mut().for_each(|x| *x /= norm);
        }
        let mut qd = uniform(nv, 10.0);
        qd[k % nv] = if k % 2 == 0 { 0.0 } else { -0.0 };
        let mut state = State {
            q,
            qd,
            qdd: uniform(nv, 10.0),
            tau: uniform(nv, 50.0),
            standard: uniform(module.dims.np, 2.0),
        };
        let joints = module.nq - if module.floating_base { 7 } else { 0 };
        match k {
            1 => {
                let zero = |v: &mut Vec<f64>| v.iter_mut().for_each(|x| *x = 0.0);
                zero(&mut state.qd);
                zero(&mut state.qdd);
                if !module.floating_base {
                    zero(&mut state.q);
                }
            }
            2 if joints > 0 => state.q[module.nq - 1] = 1.0e7 + 0.25,
            _ => {}
        }
        state
    }

    /// The array `input` of this state.
    fn array(&self, input: rne_codegen::Input) -> &[f64] {
        match input {
            rne_codegen::Input::Q => &self.q,
            rne_codegen::Input::Qd => &self.qd,
            rne_codegen::Input::Qdd => &self.qdd,
            rne_codegen::Input::Tau => &self.tau,
            rne_codegen::Input::Standard => &self.standard,
        }
    }
}

/// The lengths of the arrays a kernel writes (none for a scalar, which it returns).
fn out_lengths(kernel: Kernel, program: &Program, nv: usize) -> Vec<usize> {
    match kernel.shape() {
        Shape::Scalar => Vec::new(),
        Shape::Matrices(n) => vec![nv * nv; n],
        _ => vec![program.outputs.len()],
    }
}

/// A C program that calls each of `module`'s kernels on `STATES` states read from the file
/// it is given (each state's input arrays in turn, as doubles) and writes every result to
/// its standard output, as doubles: through the header alone, linked with the kernels'
/// object file. With runtime parameters it passes the defaults.
fn driver(name: &str, module: &GeneratedPrograms) -> String {
    let mut c = format!(
        "#include \"{name}.h\"\n#include <stdio.h>\n#include <stdlib.h>\n\n\
         static FILE *in;\n\
         static void get(double *x, int n) {{\n    if (fread(x, sizeof *x, (size_t)n, in) != (size_t)n) exit(2);\n}}\n\
         static void put(const double *x, int n) {{ fwrite(x, sizeof *x, (size_t)n, stdout); }}\n\n\
         int main(int argc, char **argv) {{\n    int s;\n    if (argc < 2 || !(in = fopen(argv[1], \"rb\"))) return 1;\n"
    );
    let params = match module.parameter_mode {
        ParameterMode::Constant => String::new(),
        _ => format!("&{name}_default_params, "),
    };
    for rne_codegen_core::KernelProgram {
        kernel, program, ..
    } in &module.kernels
    {
        let mut arguments: Vec<String> = Vec::new();
        c.push_str("    {\n");
        for input in kernel.inputs() {
            let len = match input {
                rne_codegen::Input::Q => module.nq,
                rne_codegen::Input::Standard => module.dims.np,
                _ => module.dims.nv,
            };
            writeln!(c, "        double {}[{len}];", input.name()).unwrap();
            arguments.push(input.name().to_owned());
        }
        let outs = out_lengths(*kernel, program, module.dims.nv);
        for (k, len) in outs.iter().enumerate() {
            writeln!(c, "        double o{k}[{len}];").unwrap();
            arguments.push(format!("o{k}"));
        }
        writeln!(c, "        for (s = 0; s < {STATES}; s++) {{").unwrap();
        for input in kernel.inputs() {
            writeln!(
                c,
                "            get({0}, (int)(sizeof {0} / sizeof *{0}));",
                input.name()
            )
            .unwrap();
        }
        let call = format!("{name}_{}({params}{})", kernel.name(), arguments.join(", "));
        if outs.is_empty() {
            writeln!(c, "            {{\n                const double r = {call};\n                put(&r, 1);\n            }}").unwrap();
        } else {
            writeln!(c, "            {call};").unwrap();
            for (k, len) in outs.iter().enumerate() {
                writeln!(c, "            put(o{k}, {len});").unwrap();
            }
        }
        c.push_str("        }\n    }\n");
    }
    c.push_str("    return 0;\n}\n");
    c
}

/// A module's C, built and run on seeded states, with what the Rust side computes.
struct Case {
    label: String,
    module: GeneratedPrograms,
    c: CModule,
    /// Each kernel's states, in the module's order.
    states: Vec<Vec<State>>,
}

impl Case {
    fn new(label: &str, model: &RobotModel, options: &GenerationOptions, seed: u64) -> Case {
        Case::in_scene(label, model, &Scene::default(), options, seed)
    }

    /// The same in `scene`.
    fn in_scene(
        label: &str,
        model: &RobotModel,
        scene: &Scene,
        options: &GenerationOptions,
        seed: u64,
    ) -> Case {
        let module =
            generate_programs(model, scene, options, label).expect("the programs are built");
        let c = emit_c(&module, label).expect("the C is written");
        let mut rng = common::rng(seed);
        let states = module
            .kernels
            .iter()
            .map(|_| {
                (0..STATES)
                    .map(|k| State::random(&module, &mut rng, k))
                    .collect()
            })
            .collect();
        Case {
            label: label.to_owned(),
            module,
            c,
            states,
        }
    }

    /// Compiles the kernels and the driver (and checks the source and the header compile as
    /// C++), runs the driver and returns each kernel's results, state by state.
    fn run_c(&self, compilers: &Compilers, flags: &[String], tag: &str) -> Vec<Vec<Vec<f64>>> {
        let dir = scratch(&format!("{}{tag}", self.label));
        let name = &self.c.name;
        std::fs::write(dir.join(format!("{name}.h")), &self.c.header).unwrap();
        std::fs::write(dir.join(format!("{name}.c")), &self.c.source).unwrap();
        std::fs::write(dir.join("driver.c"), driver(name, &self.module)).unwrap();
        let object = dir.join(format!("{name}.o"));
        run(Command::new(&compilers.cc)
            .args(flags)
            .arg("-c")
            .arg(dir.join(format!("{name}.c")))
            .arg("-o")
            .arg(&object));
        if let Some(cxx) = &compilers.cxx {
            run(Command::new(cxx)
                .args([
                    "-x",
                    "c++",
                    "-std=c++11",
                    "-Wall",
                    "-Wextra",
                    "-pedantic",
                    "-Werror",
                ])
                .arg("-fsyntax-only")
                .arg(dir.join(format!("{name}.c"))));
        }
        let exe = dir.join("driver");
        run(Command::new(&compilers.cc)
            .args(flags)
            .arg(dir.join("driver.c"))
            .arg(&object)
            .arg("-lm")
            .arg("-o")
            .arg(&exe));
        let mut input: Vec<u8> = Vec::new();
        for (rne_codegen_core::KernelProgram { kernel, .. }, states) in
            self.module.kernels.iter().zip(&self.states)
        {
            for state in states {
                for &array in kernel.inputs() {
                    input.extend(state.array(array).iter().flat_map(|x| x.to_ne_bytes()));
                }
            }
        }
        let input_file = dir.join("states.bin");
        std::fs::write(&input_file, input).unwrap();
        let output = run(Command::new(&exe).arg(&input_file));
        let mut values = output
            .chunks_exact(8)
            .map(|b| f64::from_ne_bytes(b.try_into().unwrap()));
        let results = self
            .module
            .kernels
            .iter()
            .map(|kp| {
                (0..STATES)
                    .map(|_| values.by_ref().take(kp.program.outputs.len()).collect())
                    .collect()
            })
            .collect();
        assert!(
            values.next().is_none(),
            "{}: the driver wrote too much",
            self.label
        );
        results
    }

    /// `program` evaluated at `state` in `f64`, as the emitted Rust computes it.
    fn eval(&self, kernel: Kernel, program: &Program, state: &State) -> Vec<f64> {
        let reads_standard = kernel.inputs().contains(&rne_codegen::Input::Standard);
        program.eval(|symbol| match symbol {
            Symbol::Position(k) => state.q[usize::from(k)],
            Symbol::Velocity(k) => state.qd[usize::from(k)],
            Symbol::Acceleration(k) => state.qdd[usize::from(k)],
            Symbol::Force(k) => state.tau[usize::from(k)],
            Symbol::Parameter(i) if reads_standard => state.standard[usize::from(i)],
            Symbol::Parameter(i) => {
                let name = &self.module.parameter_symbols[usize::from(i)];
                let parameter = self
                    .module
                    .runtime_parameters
                    .iter()
                    .find(|p| &p.name == name);
                parameter.expect("a runtime parameter").value
            }
            Symbol::Lane(_) => panic!("a C kernel reads no lane"),
        })
    }

    /// Builds and runs the C and checks every result: bit for bit the program's, and bit for
    /// bit `compiled`'s (the compiled Rust kernel's, where there is one) unless `tolerance`
    /// allows a relative difference at state k (`tolerance(k)`). Returns how many results were
    /// compared with compiled kernels.
    fn check(
        &self,
        compilers: &Compilers,
        compiled: &dyn Fn(Kernel, &State) -> Option<Vec<f64>>,
        tolerance: &dyn Fn(usize) -> f64,
    ) -> usize {
        let results = self.run_c(compilers, &c_flags(), "");
        let mut compared = 0;
        for (
            (
                rne_codegen_core::KernelProgram {
                    kernel, program, ..
                },
                states,
            ),
            results,
        ) in self.module.kernels.iter().zip(&self.states).zip(results)
        {
            for (s, (state, c)) in states.iter().zip(results).enumerate() {
                let context = format!("{} {kernel} state {s}", self.label);
                assert_bits(&c, &self.eval(*kernel, program, state), &context);
                if let Some(rust) = compiled(*kernel, state) {
                    compared += 1;
                    match tolerance(s) {
                        0.0 => assert_bits(&c, &rust, &format!("{context} (compiled)")),
                        tolerance => assert_close(&c, &rust, tolerance, &context),
                    }
                }
            }
        }
        compared
    }
}

/// `a` and `b` bit for bit.
fn assert_bits(a: &[f64], b: &[f64], context: &str) {
    assert_eq!(a.len(), b.len(), "{context}: lengths");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            x.to_bits() == y.to_bits(),
            "{context}: output {k} is {x:e} in C and {y:e} in Rust"
        );
    }
}

/// `a` within `tolerance` of `b`, relative to b's largest entry.
fn assert_close(a: &[f64], b: &[f64], tolerance: f64, context: &str) {
    let error = common::rel_err_floor(a, b, f64::MIN_POSITIVE);
    assert!(error <= tolerance, "{context}: relative error {error:e}");
}

/// A built-in robot read as the macro reads it.
fn builtin(name: &str, symbolic_parameters: bool) -> RobotModel {
    let robot = rne_models::builtin(name).expect("a built-in robot");
    let options = LoadOptions {
        symbolic_parameters,
        ..LoadOptions::default()
    };
    RobotSource::Builtin(robot)
        .load(&options)
        .expect("it loads")
}

/// A robot of `tests/fixtures/robots`.
fn fixture(file: &str, symbolic_parameters: bool) -> RobotModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/robots")
        .join(file);
    let options = LoadOptions {
        symbolic_parameters,
        ..LoadOptions::default()
    };
    read_robot(Description::file(&path), &options).expect("it loads")
}

/// `outputs` with the default options and `parameters`.
fn options(outputs: &[Kernel], parameters: ParameterMode) -> GenerationOptions {
    GenerationOptions {
        outputs: outputs.to_vec(),
        parameters,
        ..GenerationOptions::default()
    }
}

/// The arrays of `v`'s length.
fn arr<const N: usize>(v: &[f64]) -> [f64; N] {
    v.try_into().expect("an array of the kernel's size")
}

/// A kernel's result as its numbers in output order (row-major, tuples in turn).
trait Flat {
    fn flat(&self, out: &mut Vec<f64>);
    fn to_flat(&self) -> Vec<f64> {
        let mut out = Vec::new();
        self.flat(&mut out);
        out
    }
}

impl Flat for f64 {
    fn flat(&self, out: &mut Vec<f64>) {
        out.push(*self);
    }
}

impl<T: Flat, const N: usize> Flat for [T; N] {
    fn flat(&self, out: &mut Vec<f64>) {
        self.iter().for_each(|x| x.flat(out));
    }
}

impl<A: Flat, B: Flat> Flat for (A, B) {
    fn flat(&self, out: &mut Vec<f64>) {
        self.0.flat(out);
        self.1.flat(out);
    }
}

impl<A: Flat, B: Flat, C: Flat> Flat for (A, B, C) {
    fn flat(&self, out: &mut Vec<f64>) {
        self.0.flat(out);
        self.1.flat(out);
        self.2.flat(out);
    }
}

/// The call of kernel `$kernel` of the generated module `$m` at state `$s` (with `(p)`, the
/// default runtime parameters first), its result flattened.
macro_rules! call {
    ($m:ident, $s:ident, ($($p:ident)?), inverse_dynamics) => {{
        $(let $p = $m::Params::default();)?
        $m::inverse_dynamics($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.qdd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), inverse_dynamics_derivatives) => {{
        $(let $p = $m::Params::default();)?
        $m::inverse_dynamics_derivatives($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.qdd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), regressor) => {{
        $(let $p = $m::Params::default();)?
        $m::regressor($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.qdd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), base_regressor) => {{
        $(let $p = $m::Params::default();)?
        $m::base_regressor($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.qdd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), mass_matrix) => {{
        $(let $p = $m::Params::default();)?
        $m::mass_matrix($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), gravity_torques) => {{
        $(let $p = $m::Params::default();)?
        $m::gravity_torques($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), potential_energy) => {{
        $(let $p = $m::Params::default();)?
        $m::potential_energy($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), mass_matrix_inverse) => {{
        $(let $p = $m::Params::default();)?
        $m::mass_matrix_inverse($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), frame_placements) => {{
        $(let $p = $m::Params::default();)?
        $m::frame_placements($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), frame_jacobians) => {{
        $(let $p = $m::Params::default();)?
        $m::frame_jacobians($(&$p,)? &arr(&$s.q)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), coriolis_matrix) => {{
        $(let $p = $m::Params::default();)?
        $m::coriolis_matrix($(&$p,)? &arr(&$s.q), &arr(&$s.qd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), bias_torques) => {{
        $(let $p = $m::Params::default();)?
        $m::bias_torques($(&$p,)? &arr(&$s.q), &arr(&$s.qd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), kinetic_energy) => {{
        $(let $p = $m::Params::default();)?
        $m::kinetic_energy($(&$p,)? &arr(&$s.q), &arr(&$s.qd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), frame_jacobian_dot_qd) => {{
        $(let $p = $m::Params::default();)?
        $m::frame_jacobian_dot_qd($(&$p,)? &arr(&$s.q), &arr(&$s.qd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), forward_dynamics) => {{
        $(let $p = $m::Params::default();)?
        $m::forward_dynamics($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.tau)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), forward_dynamics_derivatives) => {{
        $(let $p = $m::Params::default();)?
        $m::forward_dynamics_derivatives($(&$p,)? &arr(&$s.q), &arr(&$s.qd), &arr(&$s.tau)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), friction_torques) => {{
        $(let $p = $m::Params::default();)?
        $m::friction_torques($(&$p,)? &arr(&$s.qd)).to_flat()
    }};
    ($m:ident, $s:ident, ($($p:ident)?), base_parameters) => {{
        $(let $p = $m::Params::default();)?
        $m::base_parameters($(&$p,)? &arr(&$s.standard)).to_flat()
    }};
}

/// The compiled kernels `$kernel…` of the module `$m` (a path) as a function of a kernel and
/// a state, `None` for a kernel it does not have; `(p)` passes `Params::default()` first,
/// `()` nothing.
macro_rules! compiled {
    ($($m:ident)::+, $params:tt; $($kernel:ident),+) => {
        |kernel: Kernel, s: &State| -> Option<Vec<f64>> {
            use $($m)::+ as m;
            $(
                if kernel == stringify!($kernel).parse::<Kernel>().unwrap() {
                    return Some(call!(m, s, $params, $kernel));
                }
            )+
            None
        }
    };
}

/// The dynamics kernels of a built-in robot's module, through [`Dynamics`].
struct Dynamic<'a> {
    kernel: Kernel,
    state: &'a State,
}

impl Visitor for Dynamic<'_> {
    type Output = Option<Vec<f64>>;
    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, m: D) -> Option<Vec<f64>> {
        let s = self.state;
        let (q, qd, qdd, tau) = (arr(&s.q), arr(&s.qd), arr(&s.qdd), arr(&s.tau));
        match self.kernel {
            Kernel::InverseDynamics => m.inverse_dynamics(&q, &qd, &qdd).map(|r| r.to_flat()),
            Kernel::MassMatrix => m.mass_matrix(&q).map(|r| r.to_flat()),
            Kernel::CoriolisMatrix => m.coriolis_matrix(&q, &qd).map(|r| r.to_flat()),
            Kernel::GravityTorques => m.gravity_torques(&q).map(|r| r.to_flat()),
            Kernel::BiasTorques => m.bias_torques(&q, &qd).map(|r| r.to_flat()),
            Kernel::ForwardDynamics => m.forward_dynamics(&q, &qd, &tau).map(|r| r.to_flat()),
            Kernel::KineticEnergy => m.kinetic_energy(&q, &qd).map(|r| vec![r]),
            Kernel::PotentialEnergy => m.potential_energy(&q).map(|r| vec![r]),
            _ => None,
        }
    }
}

/// The compiled rne-models kernels of built-in robot `name`: its dynamics, and a URDF
/// robot's control kernels (`control` variant).
fn builtin_compiled(name: &str, kernel: Kernel, state: &State) -> Option<Vec<f64>> {
    let robot = rne_models::builtin(name).expect("a built-in robot");
    if let Some(values) = robot.visit(Dynamic { kernel, state }) {
        return Some(values);
    }
    let control = match name {
        "ur5" => compiled!(rne_models::generated::variants::ur5::control, ();
            inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse,
            frame_jacobians, frame_jacobian_dot_qd, regressor, base_parameters),
        "panda" => compiled!(rne_models::generated::variants::panda::control, ();
            inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse,
            frame_jacobians, frame_jacobian_dot_qd, regressor, base_parameters),
        "panda-arm" => compiled!(rne_models::generated::variants::panda_arm::control, ();
            inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse,
            frame_jacobians, frame_jacobian_dot_qd, regressor, base_parameters),
        _ => return None,
    };
    control(kernel, state)
}

/// Whether the rne-models kernels of a URDF robot were built with `fma: true` (its feature
/// `fma`): the C is then emitted with fused multiply-adds too.
fn urdf_fused(name: &str) -> bool {
    rne_models::generated::FUSED_MULTIPLY_ADD && is_urdf(name)
}

/// Whether the rne-models derivative kernels of a URDF robot were built with
/// `derivatives: lanes` (its feature `derivative-lanes`): the C's, built in scalars, are then
/// compared with the programs only.
fn urdf_in_lanes(name: &str) -> bool {
    rne_models::generated::DERIVATIVE_LANES && is_urdf(name)
}

/// Whether the built-in robot `name` is read from a URDF file.
fn is_urdf(name: &str) -> bool {
    rne_models::builtin(name).unwrap().file.ends_with(".urdf")
}

/// Runs `check` on each case on as many threads as the machine has cores (each case compiles
/// its C with the system compiler).
fn each_in_parallel<T: Sync>(cases: &[T], check: impl Fn(&T) + Sync) {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for _ in 0..threads.min(cases.len()) {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                match cases.get(k) {
                    Some(case) => check(case),
                    None => break,
                }
            });
        }
    });
}

/// Every kernel of every built-in robot: the C equals the programs bit for bit, and the
/// compiled rne-models kernels (every robot's dynamics, the URDF robots' control kernels).
#[test]
fn every_builtin_robots_c_kernels_equal_the_rust_kernels_bit_for_bit() {
    let Some(compilers) = compilers() else { return };
    let cases: Vec<Case> = BUILTIN_ROBOTS
        .iter()
        .enumerate()
        .map(|(k, robot)| {
            let options = GenerationOptions {
                fma: urdf_fused(robot.name),
                ..options(&Kernel::ALL, ParameterMode::Constant)
            };
            Case::new(
                robot.name,
                &builtin(robot.name, false),
                &options,
                0xC0DE + k as u64,
            )
        })
        .collect();
    each_in_parallel(&cases, |case| {
        let derivatives = [
            Kernel::InverseDynamicsDerivatives,
            Kernel::ForwardDynamicsDerivatives,
        ];
        let compiled = |kernel: Kernel, state: &State| match urdf_in_lanes(&case.label)
            && derivatives.contains(&kernel)
        {
            true => None,
            false => builtin_compiled(&case.label, kernel, state),
        };
        let compared = case.check(&compilers, &compiled, &|_| 0.0);
        let dynamics = Kernel::DYNAMICS.len() * STATES;
        assert!(
            compared >= dynamics,
            "{}: {compared} results compared",
            case.label
        );
    });
}

/// The runtime parameters of the TOML robots that have them, as `struct <robot>_params` with
/// the spec's values, against rne-models' `runtime` variants.
#[test]
fn runtime_parameters_give_the_rust_kernels_values() {
    let Some(compilers) = compilers() else { return };
    let outputs = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::BiasTorques,
        Kernel::ForwardDynamics,
    ];
    let cases: Vec<Case> = ["planar-elbow", "irb140-3dof", "irb140"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let options = options(&outputs, ParameterMode::Runtime);
            // A label of its own: the cases' scratch directories are named after them.
            let label = format!("{name}-runtime");
            Case::new(&label, &builtin(name, true), &options, 0xBA5E + k as u64)
        })
        .collect();
    for case in &cases {
        assert!(case
            .c
            .header
            .contains(&format!("struct {}_params {{", case.c.name)));
    }
    each_in_parallel(&cases, |case| {
        let compiled = match case.label.as_str() {
            "planar-elbow-runtime" => {
                compiled!(rne_models::generated::variants::planar_elbow::runtime, (p);
                inverse_dynamics, mass_matrix, bias_torques, forward_dynamics)
            }
            "irb140-3dof-runtime" => {
                compiled!(rne_models::generated::variants::irb140_3dof::runtime, (p);
                inverse_dynamics, mass_matrix, bias_torques, forward_dynamics)
            }
            "irb140-runtime" => compiled!(rne_models::generated::variants::irb140::runtime, (p);
                inverse_dynamics, mass_matrix, bias_torques, forward_dynamics),
            other => panic!("no runtime variant for {other}"),
        };
        let compared = case.check(&compilers, &compiled, &|_| 0.0);
        assert_eq!(compared, outputs.len() * STATES, "{}", case.label);
    });
}

/// Modules generated here: UR5 with every kernel (a compiled Rust kernel for each), a
/// floating base, friction and a mimic joint, and base parameters; and UR5's derivatives
/// built in lanes, which C builds in
/// scalars: within 1e-15 of them (relative to the largest entry) at random states, 2e-14 at
/// the zero state.
#[test]
fn every_kernel_a_floating_base_and_base_parameters_equal_the_compiled_rust() {
    let Some(compilers) = compilers() else { return };
    let cases = vec![
        Case::new(
            "ur5_all",
            &fixture("ur5.urdf", false),
            &options(&Kernel::ALL, ParameterMode::Constant),
            1,
        ),
        Case::new(
            "hopper",
            &fixture("hopper-floating.toml", false),
            &options(
                &[
                    Kernel::InverseDynamics,
                    Kernel::MassMatrix,
                    Kernel::ForwardDynamics,
                    Kernel::InverseDynamicsDerivatives,
                    Kernel::FramePlacements,
                ],
                ParameterMode::Constant,
            ),
            2,
        ),
        Case::in_scene(
            "geared",
            &fixture("geared-arm.toml", false),
            &Scene {
                friction: true,
                ..Scene::default()
            },
            &options(
                &[
                    Kernel::InverseDynamics,
                    Kernel::MassMatrix,
                    Kernel::ForwardDynamics,
                    Kernel::FrictionTorques,
                    Kernel::InverseDynamicsDerivatives,
                    Kernel::FramePlacements,
                ],
                ParameterMode::Constant,
            ),
            7,
        ),
        Case::new(
            "elbow_base",
            &fixture("planar-elbow.toml", false),
            &options(
                &[
                    Kernel::InverseDynamics,
                    Kernel::MassMatrix,
                    Kernel::BaseRegressor,
                ],
                ParameterMode::Base,
            ),
            3,
        ),
        Case::new(
            "ur5_lanes",
            &fixture("ur5.urdf", false),
            &options(
                &[
                    Kernel::InverseDynamicsDerivatives,
                    Kernel::ForwardDynamicsDerivatives,
                ],
                ParameterMode::Constant,
            ),
            4,
        ),
    ];
    let geared_c = &cases[2].c.source;
    for helper in ["rne_sign(", "rne_sin(", "rne_cos("] {
        assert!(geared_c.contains(helper), "the geared arm calls {helper}");
    }
    let from_standard = format!("void {}_params_from_standard(", cases[3].c.name);
    assert!(cases[3].c.header.contains(&from_standard));
    each_in_parallel(&cases, |case| {
        type Compiled = Box<dyn Fn(Kernel, &State) -> Option<Vec<f64>>>;
        let (compiled, tolerance): (Compiled, fn(usize) -> f64) = match case.label.as_str() {
            "ur5_all" => (
                Box::new(
                    compiled!(ur5_all, (); inverse_dynamics, mass_matrix, coriolis_matrix,
                    gravity_torques, bias_torques, forward_dynamics, kinetic_energy,
                    potential_energy, inverse_dynamics_derivatives, forward_dynamics_derivatives,
                    mass_matrix_inverse, frame_placements, frame_jacobians, frame_jacobian_dot_qd,
                    friction_torques, regressor, base_regressor, base_parameters),
                ),
                |_| 0.0,
            ),
            "hopper" => (
                Box::new(
                    compiled!(hopper, (); inverse_dynamics, mass_matrix, forward_dynamics,
                    inverse_dynamics_derivatives, frame_placements),
                ),
                |_| 0.0,
            ),
            "geared" => (
                Box::new(
                    compiled!(geared, (); inverse_dynamics, mass_matrix, forward_dynamics,
                    friction_torques, inverse_dynamics_derivatives, frame_placements),
                ),
                |_| 0.0,
            ),
            "elbow_base" => (
                Box::new(
                    compiled!(elbow_base, (p); inverse_dynamics, mass_matrix, base_regressor,
                    base_parameters),
                ),
                |_| 0.0,
            ),
            _ => (
                Box::new(compiled!(ur5_lanes, (); inverse_dynamics_derivatives,
                    forward_dynamics_derivatives)),
                // Measured: at most 9.4e-16 at the random states; 1.0e-14 at q = q̇ = q̈ = 0
                // (state 1), where the largest entries are gravity's alone.
                |s| if s == 1 { 2e-14 } else { 1e-15 },
            ),
        };
        let compared = case.check(&compilers, &*compiled, &tolerance);
        assert_eq!(
            compared,
            case.module.kernels.len() * STATES,
            "{}",
            case.label
        );
    });
}

/// `<robot>_params_from_standard` gives the base parameters `Params::from_standard` gives:
/// the kernels agree bit for bit at random standard parameters.
#[test]
fn base_parameters_from_standard_parameters_equal_the_rusts() {
    let Some(compilers) = compilers() else { return };
    let outputs = [Kernel::InverseDynamics];
    let case = Case::new(
        "from_standard",
        &fixture("planar-elbow.toml", false),
        &options(&outputs, ParameterMode::Base),
        6,
    );
    let (name, np) = (&case.c.name, case.module.dims.np);
    let dir = scratch("from_standard");
    std::fs::write(dir.join(format!("{name}.h")), &case.c.header).unwrap();
    std::fs::write(dir.join(format!("{name}.c")), &case.c.source).unwrap();
    std::fs::write(
        dir.join("main.c"),
        format!(
            "#include \"{name}.h\"\n#include <stdio.h>\n\
             int main(void) {{\n    double standard[{np}], q[2], qd[2], qdd[2], tau[2];\n    struct {name}_params p;\n    \
             while (fread(standard, sizeof(double), {np}, stdin) == {np} && fread(q, sizeof q, 1, stdin) == 1\n           \
             && fread(qd, sizeof qd, 1, stdin) == 1 && fread(qdd, sizeof qdd, 1, stdin) == 1) {{\n        \
             {name}_params_from_standard(standard, &p);\n        {name}_inverse_dynamics(&p, q, qd, qdd, tau);\n        \
             fwrite(tau, sizeof tau, 1, stdout);\n    }}\n    return 0;\n}}\n"
        ),
    )
    .unwrap();
    let exe = dir.join("main");
    run(Command::new(&compilers.cc)
        .args(c_flags())
        .arg(dir.join("main.c"))
        .arg(dir.join(format!("{name}.c")))
        .arg("-lm")
        .arg("-o")
        .arg(&exe));
    let mut rng = common::rng(0xF5);
    let mut input: Vec<f64> = Vec::new();
    let mut expected: Vec<f64> = Vec::new();
    for _ in 0..STATES {
        let standard: Vec<f64> = (0..np).map(|_| rng.gen_range(-2.0..=2.0)).collect();
        let (q, qd, qdd) = common::state(&mut rng, 2);
        let p = elbow_base::Params::from_standard(&arr(&standard));
        expected.extend(elbow_base::inverse_dynamics(
            &p,
            &arr(&q),
            &arr(&qd),
            &arr(&qdd),
        ));
        input.extend(standard.iter().chain(&q).chain(&qd).chain(&qdd));
    }
    let bytes: Vec<u8> = input.iter().flat_map(|x| x.to_ne_bytes()).collect();
    std::fs::write(dir.join("input.bin"), bytes).unwrap();
    let output = run(Command::new(&exe).stdin(std::fs::File::open(dir.join("input.bin")).unwrap()));
    let values: Vec<f64> = output
        .chunks_exact(8)
        .map(|b| f64::from_ne_bytes(b.try_into().unwrap()))
        .collect();
    assert_bits(
        &values,
        &expected,
        "inverse dynamics at base parameters from standard ones",
    );
}

/// The C's sine and cosine (`rne_sin_cos`) are the runtime's `sin_cos` bit for bit: joint
/// angles, the fast path's whole range, the Payne–Hanek reduction's (up to the largest
/// double, and the double nearest a multiple of π/2), zeros, subnormals, infinities and NaN.
#[test]
fn the_c_sine_and_cosine_are_the_runtimes_bit_for_bit() {
    let Some(compilers) = compilers() else { return };
    let case = Case::new(
        "trig",
        &builtin("planar-elbow", false),
        &options(&[Kernel::MassMatrix], ParameterMode::Constant),
        5,
    );
    let mut rng = common::rng(0x5105);
    let mut arguments: Vec<f64> = vec![
        0.0,
        -0.0,
        1.0,
        5e-324,
        -2.2e-308,
        1e-8,
        f64::MAX,
        -f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        6_381_956_970_095_103.0 * 2f64.powi(797),
        1_048_576.0 * std::f64::consts::FRAC_PI_2,
        -1_048_576.0 * std::f64::consts::FRAC_PI_2,
        1e22,
        2f64.powi(53),
    ];
    for k in -8..=8 {
        let x = f64::from(k) * std::f64::consts::FRAC_PI_4;
        arguments.extend([
            x,
            f64::from_bits(x.to_bits() + 1),
            f64::from_bits(x.to_bits().saturating_sub(1)),
        ]);
    }
    arguments.extend((0..20_000).map(|_| rng.gen_range(-100.0..=100.0)));
    arguments.extend((0..5_000).map(|_| rng.gen_range(-2.0e6..=2.0e6)));
    arguments.extend((0..5_000).map(|_| {
        let magnitude = rng.gen_range(1.0..2.0) * 2f64.powi(rng.gen_range(-1074..1024));
        if rng.gen() {
            magnitude
        } else {
            -magnitude
        }
    }));
    let dir = scratch("trig");
    std::fs::write(dir.join("robot.h"), &case.c.header).unwrap();
    let source = case.c.source.replace(
        &format!("#include \"{}.h\"", case.c.name),
        "#include \"robot.h\"",
    );
    std::fs::write(dir.join("robot.c"), source).unwrap();
    std::fs::write(
        dir.join("trig.c"),
        "#include \"robot.c\"\n#include <stdio.h>\n\
         int main(void) {\n    double x, s, c;\n    while (fread(&x, sizeof x, 1, stdin) == 1) {\n        \
         rne_sin_cos(x, &s, &c);\n        fwrite(&s, sizeof s, 1, stdout);\n        fwrite(&c, sizeof c, 1, stdout);\n    }\n    return 0;\n}\n",
    )
    .unwrap();
    let exe = dir.join("trig");
    run(Command::new(&compilers.cc)
        .args(c_flags())
        .arg(dir.join("trig.c"))
        .arg("-lm")
        .arg("-o")
        .arg(&exe));
    let input: Vec<u8> = arguments.iter().flat_map(|x| x.to_ne_bytes()).collect();
    std::fs::write(dir.join("arguments.bin"), &input).unwrap();
    let output =
        run(Command::new(&exe).stdin(std::fs::File::open(dir.join("arguments.bin")).unwrap()));
    let values: Vec<f64> = output
        .chunks_exact(8)
        .map(|b| f64::from_ne_bytes(b.try_into().unwrap()))
        .collect();
    assert_eq!(values.len(), 2 * arguments.len());
    for (k, &x) in arguments.iter().enumerate() {
        let (s, c) = rne_codegen::sin_cos(x);
        assert_bits(
            &values[2 * k..2 * k + 2],
            &[s, c],
            &format!("sin_cos({x:e})"),
        );
    }
}

/// Optimisation and GNU C, which contracts products and sums by default, change no result:
/// the C compiled with `-std=c99 -O1` and with `-std=gnu99 -O3 -march=native` (both with
/// FMA, so that a compiler could fuse) computes the same bits, split kernels included — the
/// source's pragmas keep GCC from contracting, its vectorizer too. On x86-64 processors with
/// FMA (skipped elsewhere, with a message).
#[test]
fn optimisation_and_gnu_c_change_no_result() {
    let Some(compilers) = compilers() else { return };
    #[cfg(target_arch = "x86_64")]
    let fma = std::is_x86_feature_detected!("fma");
    #[cfg(not(target_arch = "x86_64"))]
    let fma = false;
    if !fma {
        eprintln!("skipped: this processor has no FMA, which a compiler would contract with");
        return;
    }
    let outputs = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::ForwardDynamics,
        Kernel::InverseDynamicsDerivatives,
    ];
    let case = Case::new(
        "panda",
        &builtin("panda", false),
        &options(&outputs, ParameterMode::Constant),
        8,
    );
    assert!(
        case.c.source.contains("RNE_NOINLINE"),
        "∂ID is split into parts"
    );
    let strict: Vec<String> = ["-std=c99", "-O1", "-mfma"].map(str::to_owned).to_vec();
    let gnu: Vec<String> = ["-std=gnu99", "-O3", "-march=native", "-mfma"]
        .map(str::to_owned)
        .to_vec();
    let (a, b) = (
        case.run_c(&compilers, &strict, "-strict"),
        case.run_c(&compilers, &gnu, "-gnu"),
    );
    for (rne_codegen_core::KernelProgram { kernel, .. }, (a, b)) in
        case.module.kernels.iter().zip(a.iter().zip(&b))
    {
        for (s, (a, b)) in a.iter().zip(b).enumerate() {
            assert_bits(
                a,
                b,
                &format!("panda {kernel} state {s}, -O1 and -O3 -march=native"),
            );
        }
    }
}

/// The same robot, scene and options give the same bytes, header and source.
#[test]
fn the_c_is_the_same_every_time() {
    let model = builtin("panda", false);
    let options = options(&Kernel::ALL, ParameterMode::Constant);
    let first = rne_codegen_core::generate_c(&model, &Scene::default(), &options, "panda").unwrap();
    let second =
        rne_codegen_core::generate_c(&model, &Scene::default(), &options, "panda").unwrap();
    assert!(first == second, "two runs wrote different C");
    assert!(
        first.source.contains("RNE_NOINLINE"),
        "the Panda's derivatives are split into parts"
    );
}
