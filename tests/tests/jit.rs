//! The JIT (rne-jit) computes what the macro's kernels compute, bit for bit: every kernel of
//! every built-in robot, of the committed robot files on both bases, with run-time parameters
//! and with fused multiply-adds, against the same programs evaluated operation by operation
//! (`Program::eval`, which the compiled modules equal bit for bit: `control_kernels.rs`) and
//! against the compiled modules themselves; its calls refuse wrong lengths and non-finite
//! states; batches and threads give the single calls' bits; dropped models free their code.

use std::path::PathBuf;

use rne_codegen::{Dynamics, Kernel};
use rne_codegen_core::{
    read_robot, GenerationOptions, Input, ParameterMode, Program, Scene, Shape,
};
use rne_interpreted::StateRef;
use rne_jit::{Batch, JitError, JitModel, State};
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_models::Visitor;
use rne_symbolic::model::Base;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{Real, RobotModel, Symbol};

/// Seeded states of a model: q (a unit quaternion first on a floating base), q̇, q̈, τ.
struct States {
    q: Vec<Vec<f64>>,
    qd: Vec<Vec<f64>>,
    qdd: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
}

impl States {
    fn new(jit: &JitModel, count: usize, seed: u64) -> States {
        let states = rne_interpreted::agreement::random_states(jit.nq(), jit.nv(), count, seed);
        States {
            q: states.iter().map(|s| s.q.clone()).collect(),
            qd: states.iter().map(|s| s.qd.clone()).collect(),
            qdd: states.iter().map(|s| s.qdd.clone()).collect(),
            tau: states.iter().map(|s| s.tau.clone()).collect(),
        }
    }

    fn len(&self) -> usize {
        self.q.len()
    }

    /// The states' arrays laid end to end, as a batch takes them.
    fn end_to_end(&self) -> EndToEnd {
        EndToEnd([&self.q, &self.qd, &self.qdd, &self.tau].map(|v| v.concat()))
    }

    fn state(&self, k: usize) -> State<'_> {
        State {
            q: &self.q[k],
            qd: &self.qd[k],
            qdd: &self.qdd[k],
            tau: &self.tau[k],
        }
    }
}

/// q, q̇, q̈ and τ of many states, each array's states end to end.
struct EndToEnd([Vec<f64>; 4]);

impl EndToEnd {
    fn batch(&self) -> Batch<'_> {
        let [q, qd, qdd, tau] = &self.0;
        Batch { q, qd, qdd, tau }
    }
}

/// `program` at `state` with `parameters` for its parameter symbols, multiply-adds fused when
/// `fused` (as the JIT fuses them on a processor with FMA) or as the runtime's `mul_add`.
fn eval(program: &Program, state: State<'_>, parameters: &[f64], fused: bool) -> Vec<f64> {
    let input = |s: Symbol| match s {
        Symbol::Position(k) => state.q[k as usize],
        Symbol::Velocity(k) => state.qd[k as usize],
        Symbol::Acceleration(k) => state.qdd[k as usize],
        Symbol::Force(k) => state.tau[k as usize],
        Symbol::Parameter(k) => parameters[k as usize],
        Symbol::Lane(_) => f64::NAN,
    };
    if fused {
        program
            .eval(|s| Fused(input(s)))
            .iter()
            .map(|x| x.0)
            .collect()
    } else {
        program.eval_f64(&input)
    }
}

/// Whether two results are the same bits (NaN payloads included).
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Every kernel of `jit` at every state of `states` against its program (the standard
/// parameters' base map at the model's own values of them).
fn check_against_programs(jit: &JitModel, states: &States, what: &str) {
    for kp in &jit.programs().kernels {
        if kp.kernel == Kernel::BaseParameters {
            let standard: Vec<f64> = (0..jit.parameter_names().len())
                .map(|i| 0.5 + i as f64 * 0.01)
                .collect();
            let expected = eval(&kp.program, State::default(), &standard, jit.fused());
            assert!(same_bits(
                &jit.base_parameters(&standard).unwrap(),
                &expected
            ));
            continue;
        }
        let mut out = vec![0.0; kp.program.outputs.len()];
        let mut all = Vec::new();
        for k in 0..states.len() {
            let state = states.state(k);
            jit.evaluate(kp.kernel, state, &mut out).unwrap();
            let expected = eval(&kp.program, state, jit.parameters(), jit.fused());
            assert!(
                same_bits(&out, &expected),
                "{what}: `{}` at state {k} differs from its program",
                kp.kernel
            );
            all.extend(expected);
        }
        check_batch(jit, kp.kernel, states, &all, what);
    }
}

/// `kernel` over all of `states` as one batch (two states a call in two lanes, an odd last
/// one alone) gives `expected`, the states' results end to end, bit for bit.
fn check_batch(jit: &JitModel, kernel: Kernel, states: &States, expected: &[f64], what: &str) {
    let arrays = states.end_to_end();
    let batch = arrays.batch();
    let mut out = vec![0.0; expected.len()];
    jit.evaluate_batch(kernel, batch, &mut out).unwrap();
    let per = jit.output_len(kernel).unwrap_or(1).max(1);
    let first = (0..states.len()).find(|&k| {
        let at = k * per..(k + 1) * per;
        !same_bits(&out[at.clone()], &expected[at])
    });
    assert_eq!(
        first, None,
        "{what}: `{kernel}` in a batch differs at a state"
    );
    check_matrices(jit, kernel, &arrays, expected, what);
}

/// A kernel returning several matrices, batched into one array per matrix
/// (`evaluate_batch_matrices`, on one thread and on three), gives each state's matrices of
/// `expected` (the states' results end to end), bit for bit.
fn check_matrices(jit: &JitModel, kernel: Kernel, arrays: &EndToEnd, expected: &[f64], what: &str) {
    let Shape::Matrices(count) = kernel.shape() else {
        return;
    };
    let len = jit.nv() * jit.nv();
    let states = expected.len() / (count * len);
    for threads in [1, 3] {
        let mut values = vec![vec![f64::NAN; states * len]; count];
        let mut outs: Vec<&mut [f64]> = values.iter_mut().map(Vec::as_mut_slice).collect();
        match threads {
            1 => jit.evaluate_batch_matrices(kernel, arrays.batch(), &mut outs),
            t => jit.evaluate_batch_matrices_threaded(kernel, arrays.batch(), &mut outs, t),
        }
        .unwrap();
        for (k, state) in expected.chunks_exact(count * len).enumerate() {
            for (m, matrix) in state.chunks_exact(len).enumerate() {
                assert!(
                    same_bits(&values[m][k * len..(k + 1) * len], matrix),
                    "{what}: `{kernel}` matrix {m} of state {k} in its own array, {threads} threads"
                );
            }
        }
    }
}

fn all_kernels() -> GenerationOptions {
    GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        ..GenerationOptions::default()
    }
}

fn builtin(robot: &'static rne_models::BuiltinRobot) -> RobotModel {
    RobotSource::Builtin(robot)
        .load(&LoadOptions::default())
        .unwrap()
}

/// Built-in robot `name` compiled with only `kernels`.
fn builtin_with(name: &str, kernels: &[Kernel]) -> JitModel {
    let robot = rne_models::builtin::builtin(name).unwrap();
    let options = GenerationOptions {
        outputs: kernels.to_vec(),
        ..GenerationOptions::default()
    };
    JitModel::compile(&builtin(robot), &Scene::default(), &options, robot.name).unwrap()
}

/// How many seeded states the built-in robots are checked at: `RNE_JIT_STATES`, or 300 (CI's
/// debug build; docs/jit.md gives the run at 10 000).
fn builtin_states() -> usize {
    std::env::var("RNE_JIT_STATES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(300)
}

/// Every kernel of every built-in robot, fma off, at seeded states ([`builtin_states`]).
#[test]
fn every_kernel_of_every_builtin_robot_is_its_program_bit_for_bit() {
    for robot in BUILTIN_ROBOTS {
        let jit = JitModel::compile(
            &builtin(robot),
            &Scene::default(),
            &all_kernels(),
            robot.name,
        )
        .unwrap();
        assert_eq!(jit.kernels().len(), Kernel::ALL.len());
        check_against_programs(
            &jit,
            &States::new(&jit, builtin_states(), 0x717),
            robot.name,
        );
    }
}

/// Joint angles outside the fast path of the runtime's `sin_cos` (|q| ≥ 2²⁰·π/2, up to the
/// largest `f64`), in some states and not their neighbours: the compiled code computes the
/// fast path itself and sends such angles to the runtime's `sin_cos_array` (rne-jit
/// `lower/trig.rs`); every kernel of every built-in robot at both tiers still gives its
/// program's bits, in single calls and in batches where one lane of a pair is out of range.
#[test]
fn angles_beyond_the_fast_path_give_the_runtime_bits() {
    let huge = [3.0e6, -1.0e300, 1.7e7, -2.5e6, f64::MAX];
    for robot in BUILTIN_ROBOTS {
        for tier in [rne_jit::Tier::Fast, rne_jit::Tier::Optimized] {
            let model = builtin(robot);
            let scene = Scene::default();
            let jit =
                JitModel::compile_at(&model, &scene, &all_kernels(), robot.name, tier).unwrap();
            let mut states = States::new(&jit, 24, 0x71a);
            for k in (0..states.len()).filter(|k| k % 3 != 1) {
                let joint = k % jit.nq();
                states.q[k][joint] = huge[k % huge.len()];
            }
            check_against_programs(&jit, &states, &format!("{} {tier:?}", robot.name));
        }
    }
}

/// The eight dynamics kernels of every built-in robot against its compiled module (the
/// macro's `Model`, through `rne_interpreted::evaluate`), bit for bit.
#[test]
fn the_dynamics_kernels_are_the_compiled_modules_bit_for_bit() {
    for robot in BUILTIN_ROBOTS {
        let jit = JitModel::compile(
            &builtin(robot),
            &Scene::default(),
            &GenerationOptions::default(),
            robot.name,
        )
        .unwrap();
        let states = States::new(&jit, 1_000, 0x718);
        robot.visit(AgainstCompiled {
            jit: &jit,
            states: &states,
            robot: robot.name,
        });
    }
}

/// The visit comparing a built-in robot's compiled `Model` with the JIT.
struct AgainstCompiled<'a> {
    jit: &'a JitModel,
    states: &'a States,
    robot: &'a str,
}

impl Visitor for AgainstCompiled<'_> {
    type Output = ();

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, module: D) {
        for kernel in Kernel::DYNAMICS {
            for k in 0..self.states.len() {
                let s = self.states.state(k);
                let state = StateRef {
                    q: s.q,
                    qd: s.qd,
                    qdd: s.qdd,
                    tau: s.tau,
                };
                let compiled = rne_interpreted::evaluate(&module, kernel, state).unwrap();
                let jitted = self.jit.evaluate_vec(kernel, s).unwrap();
                assert!(
                    same_bits(&jitted, &compiled),
                    "{} `{kernel}` state {k}",
                    self.robot
                );
            }
        }
    }
}

/// The committed robot files (the tests' and the corpus's fixtures, Baxter, TIAGo and Iris among
/// them) on a fixed and a floating base, every kernel.
#[test]
fn every_kernel_of_the_committed_robot_files_on_both_bases() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let files = [
        root.join("fixtures/robots/ur5.urdf"),
        root.join("fixtures/robots/gripper-mimic.urdf"),
        root.join("fixtures/robots/geared-arm.toml"),
        root.join("fixtures/robots/hopper-floating.toml"),
        root.join("../rne-models/corpus/tests/fixtures/baxter.urdf"),
        root.join("../rne-models/corpus/tests/fixtures/tiago_no_hand.urdf"),
        root.join("../rne-models/corpus/tests/fixtures/iris.urdf"),
    ];
    for path in files {
        for base in [Base::Fixed, Base::Floating] {
            let scene = Scene {
                base: Some(base),
                ..Scene::default()
            };
            let what = format!("{} {base:?}", path.display());
            let file = path.display().to_string();
            let model = read_robot(&path, &file, &scene, &all_kernels()).unwrap();
            let jit = JitModel::compile(&model, &scene, &all_kernels(), &what).unwrap();
            check_against_programs(&jit, &States::new(&jit, 50, 0x719), &what);
        }
    }
}

/// Every URDF under the directory `RNE_JIT_URDF_DIR` (searched recursively; skipped when the
/// variable is unset) that rne loads, on its own base, every kernel at 20 states, compiled at
/// the fast tier (both tiers give the same bits: `both_tiers_compute_the_same_bits`). The run
/// on example-robot-data is docs/performance.md's:
/// `RNE_JIT_URDF_DIR=DIR cargo test --release -p rne-tests --test jit -- --nocapture urdfs_of`.
#[test]
fn every_kernel_of_the_urdfs_of_a_directory() {
    let Some(dir) = std::env::var_os("RNE_JIT_URDF_DIR") else {
        eprintln!("RNE_JIT_URDF_DIR is not set: no directory of URDFs to check");
        return;
    };
    let mut files = Vec::new();
    let mut folders = vec![PathBuf::from(dir)];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "urdf") {
                files.push(path);
            }
        }
    }
    files.sort();
    let (mut checked, mut refused) = (0, Vec::new());
    for path in &files {
        let what = path.display().to_string();
        let scene = Scene::default();
        let compiled = read_robot(path, &what, &scene, &all_kernels())
            .map_err(|e| e.to_string())
            .and_then(|model| {
                JitModel::compile_at(&model, &scene, &all_kernels(), &what, rne_jit::Tier::Fast)
                    .map_err(|e| e.to_string())
            });
        match compiled {
            Ok(jit) => {
                check_against_programs(&jit, &States::new(&jit, 20, 0x5eed), &what);
                checked += 1;
            }
            Err(why) => refused.push(format!("{what}: {why}")),
        }
    }
    eprintln!(
        "{} URDF files: {checked} checked bit for bit, {} not loaded:",
        files.len(),
        refused.len()
    );
    for why in &refused {
        eprintln!("  {why}");
    }
    assert!(checked > 0, "no URDF under the directory loads");
}

/// Fused multiply-adds: with `fma` on, each kernel is its fused program, rounded once per
/// multiply-add where the processor fuses (as the macro's kernel compiled for it) and twice
/// where it does not (as the runtime's `mul_add` there).
#[test]
fn with_fma_every_kernel_is_its_fused_program() {
    let options = GenerationOptions {
        fma: true,
        ..all_kernels()
    };
    for robot in BUILTIN_ROBOTS {
        let jit =
            JitModel::compile(&builtin(robot), &Scene::default(), &options, robot.name).unwrap();
        let fuses = cfg!(target_arch = "aarch64") || std::is_x86_feature_detected!("fma");
        assert_eq!(
            jit.fused(),
            fuses,
            "fused exactly where the processor has FMA"
        );
        check_against_programs(&jit, &States::new(&jit, 500, 0x71a), robot.name);
    }
}

/// Joint friction (the regressor's Coulomb columns: `sign` of the velocities, in scalars and
/// in lanes), with velocities of ±0 among the states: every kernel its program, bit for bit,
/// alone and in batches.
#[test]
fn with_friction_every_kernel_is_its_program() {
    let robot = rne_models::builtin::builtin("planar-elbow").unwrap();
    let scene = Scene {
        friction: true,
        ..Scene::default()
    };
    let jit = JitModel::compile(&builtin(robot), &scene, &all_kernels(), robot.name).unwrap();
    let has_sign = jit.programs().kernels.iter().any(|kp| {
        kp.program
            .instrs
            .iter()
            .any(|i| matches!(i, rne_codegen_core::Instr::Sign(_)))
    });
    assert!(
        has_sign,
        "friction's kernels take the sign of the velocities"
    );
    let mut states = States::new(&jit, 41, 0x7f1);
    for (k, qd) in states.qd.iter_mut().enumerate().step_by(3) {
        let n = qd.len();
        qd[k % n] = 0.0;
        qd[(k + 1) % n] = -0.0;
    }
    check_against_programs(&jit, &states, "planar-elbow with friction");
}

/// Run-time parameters: the kernels read the values set, bit for bit the program at them.
#[test]
fn runtime_parameters_are_read_at_every_call() {
    let robot = rne_models::builtin::builtin("planar-elbow").unwrap();
    let options = GenerationOptions {
        parameters: ParameterMode::Runtime,
        ..all_kernels()
    };
    let model = RobotSource::Builtin(robot)
        .load(&LoadOptions {
            symbolic_parameters: true,
            ..LoadOptions::default()
        })
        .unwrap();
    let mut jit = JitModel::compile(&model, &Scene::default(), &options, robot.name).unwrap();
    assert!(!jit.parameter_symbols().is_empty());
    let states = States::new(&jit, 200, 0x71b);
    check_against_programs(&jit, &states, "spec values");
    let doubled: Vec<f64> = jit.parameters().iter().map(|p| 2.0 * p).collect();
    let before = jit
        .evaluate_vec(Kernel::InverseDynamics, states.state(0))
        .unwrap();
    jit.set_parameters(&doubled).unwrap();
    assert_ne!(
        jit.evaluate_vec(Kernel::InverseDynamics, states.state(0))
            .unwrap(),
        before
    );
    check_against_programs(&jit, &states, "doubled parameters");
    assert!(matches!(
        jit.set_parameters(&[1.0]),
        Err(JitError::ParameterLength { got: 1, .. })
    ));
}

/// Wrong lengths, non-finite values and kernels not compiled are errors naming the kernel, the
/// array and the entry; nothing reaches the compiled code.
#[test]
fn bad_calls_are_errors() {
    let jit = builtin_with("ur5", &[Kernel::InverseDynamics, Kernel::MassMatrix]);
    let (q, v) = (vec![0.1; 6], vec![0.2; 6]);
    let state = State {
        q: &q,
        qd: &v,
        qdd: &v,
        tau: &[],
    };
    let mut out = vec![0.0; 6];
    let short = State {
        q: &q[..5],
        ..state
    };
    let error = jit
        .evaluate(Kernel::InverseDynamics, short, &mut out)
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "`inverse_dynamics`: `q` has 5 values; the robot needs 6"
    );
    let mut nan = q.clone();
    nan[3] = f64::NAN;
    let error = jit
        .evaluate(
            Kernel::InverseDynamics,
            State { q: &nan, ..state },
            &mut out,
        )
        .unwrap_err();
    assert!(
        matches!(error, JitError::NonFinite { index: 3, .. }),
        "{error}"
    );
    let mut infinite = v.clone();
    infinite[0] = f64::INFINITY;
    let error = jit
        .evaluate(
            Kernel::InverseDynamics,
            State {
                qdd: &infinite,
                ..state
            },
            &mut out,
        )
        .unwrap_err();
    assert!(error.to_string().contains("`qdd[0]` is inf"), "{error}");
    let error = jit
        .evaluate(Kernel::MassMatrix, state, &mut out)
        .unwrap_err();
    assert!(
        matches!(error, JitError::OutputLength { expected: 36, .. }),
        "{error}"
    );
    let error = jit
        .evaluate(Kernel::ForwardDynamics, state, &mut out)
        .unwrap_err();
    assert!(matches!(error, JitError::MissingKernel { .. }), "{error}");
    let batch = Batch {
        q: &q,
        qd: &v,
        qdd: &v[..3],
        tau: &[],
    };
    let error = jit
        .evaluate_batch(Kernel::InverseDynamics, batch, &mut out)
        .unwrap_err();
    assert!(matches!(error, JitError::BatchLength { .. }), "{error}");
}

/// A single call runs exactly when every array its kernel takes has the robot's length and
/// finite values, whatever the arrays it does not take hold: each kernel of UR5, each array
/// one value short, one too long, empty, or with a NaN or an infinity at each entry.
#[test]
fn a_call_is_refused_exactly_when_an_array_it_takes_is_bad() {
    let kernels: Vec<Kernel> = Kernel::ALL
        .into_iter()
        .filter(|&k| k != Kernel::BaseParameters)
        .collect();
    let jit = builtin_with("ur5", &kernels);
    let good = vec![0.3; 6];
    let mut variants: Vec<Vec<f64>> = vec![vec![0.3; 5], vec![0.3; 7], Vec::new()];
    for at in 0..6 {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut values = good.clone();
            values[at] = bad;
            variants.push(values);
        }
    }
    let inputs = [Input::Q, Input::Qd, Input::Qdd, Input::Tau];
    for &kernel in &kernels {
        let mut out = vec![0.0; jit.output_len(kernel).unwrap()];
        for (slot, input) in inputs.iter().enumerate() {
            for values in &variants {
                let mut arrays = [good.as_slice(); 4];
                arrays[slot] = values;
                let state = State {
                    q: arrays[0],
                    qd: arrays[1],
                    qdd: arrays[2],
                    tau: arrays[3],
                };
                let taken = kernel.inputs().contains(input);
                let result = jit.evaluate(kernel, state, &mut out);
                assert_eq!(
                    result.is_err(),
                    taken,
                    "{kernel:?}, {input:?} = {values:?}: {result:?}"
                );
            }
        }
    }
}

/// A batch gives each state's single call bit for bit, on one thread and on several.
#[test]
fn batches_and_threads_give_the_single_calls() {
    let jit = builtin_with(
        "panda-arm",
        &[Kernel::ForwardDynamics, Kernel::InverseDynamicsDerivatives],
    );
    let states = States::new(&jit, 333, 0x71c);
    let arrays = states.end_to_end();
    let batch = arrays.batch();
    for kernel in jit.kernels() {
        let per = jit.output_len(kernel).unwrap();
        let singles: Vec<f64> = (0..states.len())
            .flat_map(|k| jit.evaluate_vec(kernel, states.state(k)).unwrap())
            .collect();
        let mut one = vec![0.0; per * states.len()];
        jit.evaluate_batch(kernel, batch, &mut one).unwrap();
        assert!(same_bits(&one, &singles), "{kernel}: batch");
        for threads in [2, 3, 7] {
            let mut many = vec![0.0; per * states.len()];
            jit.evaluate_batch_threaded(kernel, batch, &mut many, threads)
                .unwrap();
            assert!(same_bits(&many, &singles), "{kernel}: {threads} threads");
        }
    }
}

/// A batch with bad states fails on the first of them on any number of threads, as one thread
/// does, though the threads take the states in chunks as they become free.
#[test]
fn threads_report_the_first_bad_state() {
    let jit = builtin_with("panda-arm", &[Kernel::InverseDynamics]);
    let states = States::new(&jit, 333, 0x71e);
    let mut arrays = states.end_to_end();
    let nq = jit.nq();
    // Two bad states, each with its own entry and value, in different chunks of a thread; the
    // first is the second state of a pair of lanes.
    arrays.0[0][251 * nq + 1] = f64::NAN;
    arrays.0[0][300 * nq + 4] = f64::INFINITY;
    let kernel = Kernel::InverseDynamics;
    let mut out = vec![0.0; jit.output_len(kernel).unwrap() * states.len()];
    let one = jit
        .evaluate_batch(kernel, arrays.batch(), &mut out)
        .unwrap_err();
    assert!(
        one.to_string()
            .starts_with("state 251 of the batch: `inverse_dynamics`: `q[1]` is NaN"),
        "{one}"
    );
    for threads in [2, 3, 7] {
        let many = jit
            .evaluate_batch_threaded(kernel, arrays.batch(), &mut out, threads)
            .unwrap_err();
        assert_eq!(many.to_string(), one.to_string(), "{threads} threads");
    }
    // An odd last state, called alone, is named by its number too.
    let (q, qd, qdd) = (&arrays.0[0], &arrays.0[1], &arrays.0[2]);
    let nv = jit.nv();
    let three = Batch {
        q: &q[249 * nq..252 * nq],
        qd: &qd[249 * nv..252 * nv],
        qdd: &qdd[249 * nv..252 * nv],
        tau: &[],
    };
    let per = jit.output_len(kernel).unwrap();
    let error = jit
        .evaluate_batch(kernel, three, &mut out[..3 * per])
        .unwrap_err();
    assert!(
        error.to_string().starts_with("state 2 of the batch: "),
        "{error}"
    );
}

/// A batch into one array per matrix refuses another number of arrays, a kernel that does not
/// return several matrices and arrays of the wrong length, and names its first bad state.
#[test]
fn matrix_batches_refuse_wrong_arrays_and_name_a_bad_state() {
    let jit = builtin_with(
        "ur5",
        &[Kernel::InverseDynamics, Kernel::InverseDynamicsDerivatives],
    );
    let states = States::new(&jit, 5, 0x3a7);
    let mut arrays = states.end_to_end();
    let len = jit.nv() * jit.nv();
    let kernel = Kernel::InverseDynamicsDerivatives;
    let (mut a, mut b, mut c) = (vec![0.0; 5 * len], vec![0.0; 5 * len], vec![0.0; 5 * len]);
    let error = jit
        .evaluate_batch_matrices(kernel, arrays.batch(), &mut [&mut a, &mut b, &mut c])
        .unwrap_err();
    assert!(
        matches!(
            error,
            JitError::MatrixArrays {
                got: 3,
                expected: 2,
                ..
            }
        ),
        "{error}"
    );
    let error = jit
        .evaluate_batch_matrices(Kernel::InverseDynamics, arrays.batch(), &mut [&mut a])
        .unwrap_err();
    assert!(
        matches!(error, JitError::MatrixArrays { expected: 0, .. }),
        "{error}"
    );
    let error = jit
        .evaluate_batch_matrices(kernel, arrays.batch(), &mut [&mut a, &mut b[..len]])
        .unwrap_err();
    assert!(matches!(error, JitError::OutputLength { .. }), "{error}");
    arrays.0[1][3 * jit.nv() + 2] = f64::NAN;
    let error = jit
        .evaluate_batch_matrices(kernel, arrays.batch(), &mut [&mut a, &mut b])
        .unwrap_err();
    assert!(
        error
            .to_string()
            .starts_with("state 3 of the batch: `inverse_dynamics_derivatives`: `qd[2]` is NaN"),
        "{error}"
    );
}

/// A model is `Send` and `Sync`: one compiled model serves threads at once.
#[test]
fn a_model_is_shared_between_threads() {
    fn shared<T: Send + Sync>(_: &T) {}
    let robot = rne_models::builtin::builtin("puma560").unwrap();
    let jit = JitModel::compile(
        &builtin(robot),
        &Scene::default(),
        &GenerationOptions::default(),
        robot.name,
    )
    .unwrap();
    shared(&jit);
    let states = States::new(&jit, 64, 0x71d);
    let expected: Vec<Vec<f64>> = (0..states.len())
        .map(|k| {
            jit.evaluate_vec(Kernel::MassMatrix, states.state(k))
                .unwrap()
        })
        .collect();
    std::thread::scope(|scope| {
        for _ in 0..4 {
            scope.spawn(|| {
                for (k, m) in expected.iter().enumerate() {
                    let got = jit
                        .evaluate_vec(Kernel::MassMatrix, states.state(k))
                        .unwrap();
                    assert!(same_bits(&got, m));
                }
            });
        }
    });
}

/// Resident memory after compiling and dropping a model many times stays where the first
/// models left it: dropping a model frees its code.
#[test]
#[cfg(target_os = "linux")]
fn dropped_models_free_their_code() {
    // The process's resident memory is measured, so the test runs alone in a child process of
    // this test binary: the other tests' allocations would count otherwise.
    if std::env::var_os("RNE_JIT_DROP_ALONE").is_none() {
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "--exact",
                "dropped_models_free_their_code",
                "--test-threads=1",
                "--nocapture",
            ])
            .env("RNE_JIT_DROP_ALONE", "1")
            .status()
            .unwrap();
        assert!(status.success(), "the child run failed: {status}");
        return;
    }
    let robot = rne_models::builtin::builtin("planar-elbow").unwrap();
    let model = builtin(robot);
    let options = GenerationOptions::default();
    let resident = || -> usize {
        let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
        let pages: usize = statm.split_whitespace().nth(1).unwrap().parse().unwrap();
        pages * 4096
    };
    for _ in 0..50 {
        drop(JitModel::compile(&model, &Scene::default(), &options, robot.name).unwrap());
    }
    let before = resident();
    // RNE_JIT_DROPS=10000 for the figure of docs/performance.md.
    let drops: usize = std::env::var("RNE_JIT_DROPS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(500);
    for _ in 0..drops {
        drop(JitModel::compile(&model, &Scene::default(), &options, robot.name).unwrap());
    }
    let grown = resident().saturating_sub(before);
    eprintln!("resident memory grew by {grown} bytes over {drops} models");
    // A leaked model keeps at least a page of code per kernel: 500 × 8 pages ≈ 16 MB.
    assert!(
        grown < 4 << 20,
        "resident memory grew by {grown} bytes over {drops} models"
    );
}

/// `f64` whose `mul_add` is fused: how the JIT computes on a processor with FMA.
#[derive(Copy, Clone, Debug, PartialEq, PartialOrd)]
struct Fused(f64);

macro_rules! fused_ops {
    ($($trait:ident $method:ident $op:tt),*) => {$(
        impl std::ops::$trait for Fused {
            type Output = Fused;
            fn $method(self, other: Fused) -> Fused {
                Fused(self.0 $op other.0)
            }
        }
    )*};
}
fused_ops!(Add add +, Sub sub -, Mul mul *, Div div /);

macro_rules! fused_assign_ops {
    ($($trait:ident $method:ident $op:tt),*) => {$(
        impl std::ops::$trait for Fused {
            fn $method(&mut self, other: Fused) {
                self.0 $op other.0;
            }
        }
    )*};
}
fused_assign_ops!(AddAssign add_assign +=, SubAssign sub_assign -=, MulAssign mul_assign *=);

impl std::ops::Neg for Fused {
    type Output = Fused;
    fn neg(self) -> Fused {
        Fused(-self.0)
    }
}

impl Real for Fused {
    fn from_f64(x: f64) -> Fused {
        Fused(x)
    }
    fn sin_cos(self) -> (Fused, Fused) {
        let (s, c) = self.0.sin_cos_runtime();
        (Fused(s), Fused(c))
    }
    fn sqrt(self) -> Fused {
        Fused(Real::sqrt(self.0))
    }
    fn abs(self) -> Fused {
        Fused(self.0.abs())
    }
    fn sign(self) -> Fused {
        Fused(Real::sign(self.0))
    }
    fn mul_add(self, a: Fused, b: Fused) -> Fused {
        Fused(f64::mul_add(self.0, a.0, b.0))
    }
}

/// The runtime's sine and cosine of an `f64`.
trait RuntimeTrig {
    fn sin_cos_runtime(self) -> (f64, f64);
}

impl RuntimeTrig for f64 {
    fn sin_cos_runtime(self) -> (f64, f64) {
        Real::sin_cos(self)
    }
}

/// The fast tier (single-pass register allocation) computes every kernel with the bits of the
/// optimised tier: register allocation changes where values live, not the operations.
#[test]
fn both_tiers_compute_the_same_bits() {
    let robot = rne_models::builtin::builtin("ur5").unwrap();
    let model = builtin(robot);
    let fast = JitModel::compile_at(
        &model,
        &Scene::default(),
        &all_kernels(),
        robot.name,
        rne_jit::Tier::Fast,
    )
    .unwrap();
    check_against_programs(&fast, &States::new(&fast, 200, 0x71e), "ur5, fast tier");
}

/// The optimized tier's choice of the values held in registers (rne-jit `registers.rs`) with
/// room for only two, one window for short addresses (rne-jit `windows.rs`), and programs cut
/// into parts of 300 instructions: nearly every value is stored and loaded again, from its
/// spill slot, its scratch slot or the sines' and cosines' array, through a window remade at
/// almost every access, and spill slots are reused, on every kernel of UR5 and the Panda (a
/// tree), scalars and lanes, bit for bit. The limits are read from the environment when a
/// model is compiled, so the test runs itself again in a process of its own with them set.
#[test]
fn two_registers_and_short_parts_compute_the_same_bits() {
    const NAME: &str = "two_registers_and_short_parts_compute_the_same_bits";
    if std::env::var_os("RNE_JIT_HELD").is_none() {
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .args([NAME, "--exact", "--test-threads=1"])
            .env("RNE_JIT_HELD", "2")
            .env("RNE_JIT_WINDOWS", "1")
            .env("RNE_JIT_SPLIT_ABOVE", "600")
            .env("RNE_JIT_PART_LEN", "300")
            .status()
            .unwrap();
        assert!(status.success(), "the run with two registers failed");
        return;
    }
    for name in ["ur5", "panda"] {
        let robot = rne_models::builtin::builtin(name).unwrap();
        let jit =
            JitModel::compile(&builtin(robot), &Scene::default(), &all_kernels(), name).unwrap();
        check_against_programs(&jit, &States::new(&jit, 20, 0x2e9), name);
    }
}
